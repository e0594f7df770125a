// A DEM scene stepped on several ranks against the same scene on one (DemSimulation, run on every
// rank): the grain count is kept, and the total kinetic energy and momentum track the one-rank run.
// Not bit for bit: a rank sums each grain's pair forces in its own row order (and a pair across a
// cut reaches its owner through the fold), so the forces differ in the last bits, and the pile's
// contacts amplify those differences step by step (a denser pile took them from 1e-15 to 1e-5 of the
// kinetic energy within 2000 steps). Measured here on two and three ranks: relative differences of
// the kinetic energy and momentum up to 2e-15 in the settling box (1500 steps, 19 and 34 grains
// migrated with their pair springs) and 1e-15 in the elastic gas (3000 steps); the checks allow 1e-8
// and 1e-9, far below what a wrong force or a lost spring makes (with every spring dropped at each
// rebuild, the settling box's kinetic energy was 2.4e-2 off).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <utility>

#include "systems/setup/mpi/rank_simulation.hpp"
#include "systems/decomposition/row_cost.hpp"
#include "tests/mpi/mpi_test_support.hpp"

namespace {

// A closed 40 x 20 x 20 mm box of 1 and 3 mm glass at random (seed-000 contact parameters), gravity
// along -y: the box is longest along x, so the cut between two ranks stands upright through the pile.
std::string settling_box(int small, int large, double gravity) {
  std::ostringstream s;
  s << "[run]\ndt = 1.0e-5\nduration = 0.01\nskin = 1.5e-4\nmax_overlap = 0.5\ngravity = [0.0, " << -gravity
    << ", 0.0]\n"
    << "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
    << "[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
    << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
    << "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.02, 0.02]\n"
    << "[[fill]]\nkind = \"random\"\nseed = 7\n"
    << "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.04, 0.02, 0.02] }\n"
    << "count = { small = " << small << ", large = " << large << " }\n";
  return s.str();
}

// 1 mm grains in a closed 20 mm cube, no gravity, perfectly elastic and frictionless.
std::string elastic_gas(int count) {
  std::ostringstream s;
  s << "[run]\ndt = 2.0e-6\nduration = 0.01\nskin = 1.5e-4\ngravity = [0.0, 0.0, 0.0]\n"
    << "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 0.0\nkr = 0.0\n"
    << "en = 1.0\net = 1.0\ner = 1.0\nfriction = 0.0\nrolling_friction = 0.0\n"
    << "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.02, 0.02]\n"
    << "[[fill]]\nkind = \"random\"\nseed = 11\n"
    << "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.02, 0.02, 0.02] }\n"
    << "count = { small = " << count << " }\n";
  return s.str();
}

// A velocity (each component in [-speed, speed]) that is a function of the grain's id alone.
void stir_owned(gf::Grains& g, double speed) {
  for (std::size_t r = 0; r < g.n_owned; ++r) {
    const auto id = g.pid.id[r];
    double* v[3] = {&g.vel.x[r], &g.vel.y[r], &g.vel.z[r]};
    for (std::size_t c = 0; c < 3; ++c) {
      const auto b = static_cast<unsigned>(gf::test::id_byte(id, c, 0)) << 8 | static_cast<unsigned>(gf::test::id_byte(id, c, 1));
      *v[c] = speed * (2.0 * b / 65535.0 - 1.0);
    }
  }
}

struct Totals {
  std::int64_t grains = 0;
  double energy = 0.0;                // J, translation + rotation
  std::array<double, 3> momentum{};   // kg m/s
  double momentum_scale = 0.0;        // kg m/s, sum of m |v|
};

Totals totals_one(gf::Grains& g) {
  Totals t;
  t.grains = static_cast<std::int64_t>(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double m = g.mass.m[i], v2 = g.vel.x[i] * g.vel.x[i] + g.vel.y[i] * g.vel.y[i] + g.vel.z[i] * g.vel.z[i];
    t.energy += 0.5 * m * v2;
    if (g.spin)
      t.energy += 0.5 / g.mass.inv_inertia[i] *
                  (g.omega.x[i] * g.omega.x[i] + g.omega.y[i] * g.omega.y[i] + g.omega.z[i] * g.omega.z[i]);
    t.momentum[0] += m * g.vel.x[i];
    t.momentum[1] += m * g.vel.y[i];
    t.momentum[2] += m * g.vel.z[i];
    t.momentum_scale += m * std::sqrt(v2);
  }
  return t;
}

Totals totals_ranks(gf::RankSimulation& s) {
  Totals t = totals_one(s.grains());
  const gf::MpiContext& mpi = s.mpi();
  return {mpi.sum(t.grains), mpi.sum(t.energy), {mpi.sum(t.momentum[0]), mpi.sum(t.momentum[1]), mpi.sum(t.momentum[2])},
          mpi.sum(t.momentum_scale)};
}

// Energy (J) held in the springs of overlapping pairs and wall contacts, 1/2 kn delta^2, summed over
// the ranks: pairs of owned rows with a higher row (owned or ghost: a pair across ranks is listed on
// one rank only, the higher one, which holds its ghost), walls as the faces of the box [0, side]^3.
double spring_energy(gf::Grains& g, double kn, double side, const gf::MpiContext* mpi) {
  double e = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double r = g.radius.r[i];
    for (const double x : {g.pos.x[i], g.pos.y[i], g.pos.z[i]})
      for (const double gap : {x, side - x})
        if (gap < r) e += 0.5 * kn * (r - gap) * (r - gap);
    for (std::size_t j = i + 1; j < g.n; ++j) {
      const double dx = g.pos.x[i] - g.pos.x[j], dy = g.pos.y[i] - g.pos.y[j], dz = g.pos.z[i] - g.pos.z[j];
      const double delta = r + g.radius.r[j] - std::sqrt(dx * dx + dy * dy + dz * dz);
      if (delta > 0) e += 0.5 * kn * delta * delta;
    }
  }
  return mpi ? mpi->sum(e) : e;
}

double momentum_gap(const Totals& a, const Totals& b) {
  double d = 0.0;
  for (std::size_t c = 0; c < 3; ++c) d = std::max(d, std::abs(a.momentum[c] - b.momentum[c]));
  return d / b.momentum_scale;
}

// Advances both runs by six blocks of 250 steps, checking the grain count after each and printing
// its totals; returns the largest relative kinetic-energy difference and momentum difference (of
// sum m|v|) over the blocks.
std::pair<double, double> track(gf::DemSimulation& one, gf::RankSimulation& many, const char* what) {
  const gf::MpiContext& mpi = many.mpi();
  const auto n = static_cast<std::int64_t>(one.grains().n_owned);
  double worst_e = 0.0, worst_p = 0.0;
  for (int block = 0; block < 6; ++block) {
    one.advance(250);
    many.advance(250);
    const Totals a = totals_ranks(many), b = totals_one(one.grains());
    REQUIRE(a.grains == n);
    const double de = std::abs(a.energy - b.energy) / b.energy, dp = momentum_gap(a, b);
    worst_e = std::max(worst_e, de);
    worst_p = std::max(worst_p, dp);
    if (mpi.rank() == 0)
      std::cout << what << ": step " << (block + 1) * 250 << ", kinetic energy " << a.energy << " J on " << mpi.size()
                << " ranks, " << b.energy << " J on one (relative difference " << de << "), momentum y "
                << a.momentum[1] << " / " << b.momentum[1] << " kg m/s (difference " << dp << " of sum m|v|)\n";
  }
  return {worst_e, worst_p};
}

}  // namespace

TEST_CASE("a settling box on several ranks tracks the same box on one", "[mpi][rank_step]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  const std::string scene = settling_box(300, 6, 100.0);
  gf::DemSimulation one = gf::DemSimulation::from_text(scene);
  gf::RankSimulation many = gf::RankSimulation::from_text(scene, mpi);
  const auto n = static_cast<std::int64_t>(one.grains().n_owned);
  REQUIRE(many.grains().n_owned < one.grains().n_owned);
  REQUIRE(many.total_grains() == n);
  // Thrown about as they fall, so that grains cross the cut while their contacts hold springs.
  stir_owned(one.grains(), 0.3);
  stir_owned(many.grains(), 0.3);

  const auto [worst_e, worst_p] = track(one, many, "settling");
  const gf::RankCounters& c = many.counters();
  const std::int64_t migrated = mpi.sum(c.migrated), ghosts = mpi.sum(c.ghosts);
  if (mpi.rank() == 0)
    std::cout << "settling: " << n << " grains, " << c.rebuilds << " rebuilds, " << migrated << " rows migrated, "
              << ghosts << " ghost rows now; largest relative kinetic-energy difference " << worst_e
              << ", momentum difference " << worst_p << " of sum m|v|\n";
  CHECK(migrated > 0);
  CHECK(ghosts > 0);
  CHECK(worst_e < 1e-8);
  CHECK(worst_p < 1e-8);
}

TEST_CASE("an elastic gas without gravity keeps its energy on several ranks as on one", "[mpi][rank_step]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  const std::string scene = elastic_gas(300);
  gf::DemSimulation one = gf::DemSimulation::from_text(scene);
  gf::RankSimulation many = gf::RankSimulation::from_text(scene, mpi);
  stir_owned(one.grains(), 1.0);
  stir_owned(many.grains(), 1.0);
  one.prime();
  many.prime();
  const Totals a0 = totals_ranks(many), b0 = totals_one(one.grains());
  REQUIRE(a0.energy == Approx(b0.energy).epsilon(1e-12));
  // Kinetic plus spring energy: the springs of the collisions under way hold about 2 % of it.
  auto energy_many = [&] { return totals_ranks(many).energy + spring_energy(many.grains(), 1000.0, 0.02, &mpi); };
  auto energy_one = [&] { return totals_one(one.grains()).energy + spring_energy(one.grains(), 1000.0, 0.02, nullptr); };
  const double e0_many = energy_many(), e0_one = energy_one();
  double drift_one = 0.0, drift_many = 0.0, worst_e = 0.0;
  for (int block = 0; block < 4; ++block) {
    one.advance(750);
    many.advance(750);
    REQUIRE(many.total_grains() == a0.grains);
    const double a = energy_many(), b = energy_one();
    drift_many = std::max(drift_many, std::abs(a - e0_many) / e0_many);
    drift_one = std::max(drift_one, std::abs(b - e0_one) / e0_one);
    worst_e = std::max(worst_e, std::abs(a - b) / b);
  }
  const std::int64_t migrated = mpi.sum(many.counters().migrated);
  if (mpi.rank() == 0)
    std::cout << "elastic gas: " << a0.grains << " grains, " << many.counters().rebuilds << " rebuilds, " << migrated
              << " rows migrated; largest change of kinetic + spring energy " << drift_many << " on " << mpi.size()
              << " ranks, " << drift_one << " on one; largest difference between them " << worst_e << "\n";
  CHECK(migrated > 0);
  CHECK(drift_many < 1e-3);
  CHECK(drift_one < 1e-3);
  CHECK(worst_e < 1e-9);
}

namespace {

// The settling box tipped on its end: gravity along -x, so the grains, spread over the box at the
// start (the first cut stands across x through its middle), pile up against the wall at x = 0, in
// the lowest rank's box.
std::string sliding_box() {
  std::string s = settling_box(300, 6, 100.0);
  const std::string from = "gravity = [0.0, -100", to = "gravity = [-100.0, 0";
  s.replace(s.find(from), from.size(), to);
  return s;
}

// The most owned rows on a rank over their mean.
double imbalance(gf::RankSimulation& s) {
  const auto rows = static_cast<double>(s.grains().n_owned);
  return s.mpi().max(rows) / (s.mpi().sum(rows) / s.mpi().size());
}

}  // namespace

TEST_CASE("a pile that slides into one rank's box is rebalanced and still tracks the run on one rank",
          "[mpi][rank_step]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  const std::string scene = sliding_box();
  gf::DemSimulation one = gf::DemSimulation::from_text(scene);
  gf::RankSimulation fixed = gf::RankSimulation::from_text(scene, mpi);
  gf::RankSimulation cut = gf::RankSimulation::from_text(scene, mpi);
  cut.set_rebalance(1.2);
  double worst_e = 0.0;
  for (int block = 0; block < 8; ++block) {
    one.advance(250);
    fixed.advance(250);
    cut.advance(250);
    const Totals a = totals_ranks(cut), b = totals_one(one.grains());
    REQUIRE(a.grains == b.grains);
    worst_e = std::max(worst_e, std::abs(a.energy - b.energy) / b.energy);
  }
  const double stuck = imbalance(fixed), balanced = imbalance(cut);
  if (mpi.rank() == 0)
    std::cout << "sliding: most rows over the mean " << stuck << " with the first boxes, " << balanced << " after "
              << cut.counters().rebalances << " rebalances (" << cut.counters().wide_rebuilds
              << " rebuilds exchanged among all ranks); largest relative kinetic-energy difference against one "
              << "rank " << worst_e << "\n";
  // Without rebalancing the pile sits in the first rank's box (all of it on two ranks: 2); cut again
  // at 1.2, the last rebuild left the ranks within 1.2 of the mean, and a few steps of settling
  // since then move grains by much less than the pile's width.
  CHECK(stuck > 1.5);
  CHECK(cut.counters().rebalances >= 1);
  CHECK(balanced < 1.3);
  CHECK(worst_e < 1e-8);  // as the settling box above: the rebalance moves rows, not forces

  // Stopped after the rebalance and resumed from its parts on as many ranks, it goes on bit for bit.
  const std::filesystem::path dir = std::filesystem::current_path() / "rank_simulation_test_out";
  const std::filesystem::path part = dir / ("rebalanced_" + std::to_string(mpi.size()) + "_rank" +
                                            std::to_string(mpi.rank()) + ".gfc");
  if (mpi.rank() == 0) std::filesystem::create_directories(dir);
  mpi.barrier();
  {
    gf::CheckpointWriter w;
    cut.save(w);
    w.write(part);
  }
  gf::RankSimulation resumed = gf::RankSimulation::from_text(scene, mpi);
  resumed.set_rebalance(1.2);
  resumed.restore(gf::CheckpointReader(part));
  cut.advance(300);
  resumed.advance(300);
  const Totals a = totals_ranks(cut), b = totals_ranks(resumed);
  CHECK(a.energy == b.energy);
  CHECK(a.momentum == b.momentum);
  CHECK(resumed.counters().rebalances == cut.counters().rebalances);
}

namespace {

// A dense block of 9 x 9 x 9 grains of 1 mm, 1.02 mm apart (every face neighbour listed: the skin is
// 0.15 mm), at one end of a 40 x 10 x 10 mm box, and as many grains at random in the box's other
// half, which the test sets moving: the first boxes, cut by count, put the block on one side.
std::string block_and_gas(const std::filesystem::path& csv) {
  std::ofstream f(csv);
  f << "id,type,diameter,x,y,z\n";
  int id = 0;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j)
      for (int k = 0; k < 9; ++k, ++id) {
        // x jittered by up to 5 um, so that a cut across x need not keep a whole layer together
        const double x = 0.6e-3 + 1.02e-3 * i + 5e-6 * std::sin(12.9898 * (id + 1));
        f << id << ",1,1.0e-3," << x << "," << 0.6e-3 + 1.02e-3 * j << "," << 0.6e-3 + 1.02e-3 * k << "\n";
      }
  std::ostringstream s;
  s << "[run]\ndt = 1.0e-5\nduration = 0.01\nskin = 1.5e-4\ngravity = [0.0, 0.0, 0.0]\n"
    << "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 0.0\nkr = 0.0\n"
    << "en = 1.0\net = 1.0\ner = 1.0\nfriction = 0.0\nrolling_friction = 0.0\n"
    << "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.06, 0.01, 0.01]\n"
    << "[[fill]]\nkind = \"file\"\npath = \"" << csv.string() << "\"\ntypes = { 1 = \"small\" }\n"
    << "[[fill]]\nkind = \"random\"\nseed = 4\n"
    << "region = { shape = \"box\", lo = [0.02, 0.0, 0.0], hi = [0.06, 0.01, 0.01] }\ncount = { small = 729 }\n";
  return s.str();
}

// The costliest rank's cost over the mean (systems/decomposition/row_cost.hpp).
double cost_imbalance(gf::RankSimulation& s) {
  double c = 0.0;
  for (const double x : gf::row_costs(s.grains(), s.world().resources.get<gf::NeighborList>())) c += x;
  return s.mpi().max(c) / (s.mpi().sum(c) / s.mpi().size());
}

}  // namespace

TEST_CASE("a dense block beside a gas of as many grains is rebalanced by cost, not by count", "[mpi][rank_step]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  const auto csv = std::filesystem::temp_directory_path() / ("grainflow_block_rank" + std::to_string(mpi.rank()) + ".csv");
  gf::RankSimulation s = gf::RankSimulation::from_text(block_and_gas(csv), mpi);
  std::filesystem::remove(csv);
  s.set_rebalance(1.25);
  // The gas moves at up to 0.5 m/s (so lists are rebuilt); the block stands still, its springs empty.
  gf::Grains& g = s.grains();
  for (std::size_t r = 0; r < g.n_owned; ++r)
    if (g.pid.id[r] >= 729) {
      const auto id = g.pid.id[r];
      g.vel.x[r] = 0.5 * (2.0 * static_cast<double>(gf::test::id_byte(id, 0, 0)) / 255.0 - 1.0);
      g.vel.y[r] = 0.5 * (2.0 * static_cast<double>(gf::test::id_byte(id, 1, 0)) / 255.0 - 1.0);
      g.vel.z[r] = 0.5 * (2.0 * static_cast<double>(gf::test::id_byte(id, 2, 0)) / 255.0 - 1.0);
    }
  s.prime();
  const double first = cost_imbalance(s);
  s.advance(100);
  const double after = cost_imbalance(s);
  const auto rows = static_cast<double>(s.grains().n_owned);
  const double count_imbalance = mpi.max(rows) / (mpi.sum(rows) / mpi.size());
  if (mpi.rank() == 0)
    std::cout << "block and gas on " << mpi.size() << " ranks: cost over the mean " << first << " with the first boxes, "
              << after << " after " << s.counters().rebalances << " rebalances; grains over the mean "
              << count_imbalance << "\n";
  REQUIRE(s.total_grains() == 1458);
  // Cut by count, the block's side costs about 1 + 0.46 x 2.7 = 2.2 per grain against 1 for the gas:
  // 1.38 of the mean on two ranks and on three.
  CHECK(first > 1.3);
  CHECK(s.counters().rebalances >= 1);
  // Cut by cost: within a few grains' cost of the mean (gas grains drift between rebuilds).
  CHECK(after < 1.1);
  CHECK(count_imbalance > 1.1);  // so the grain counts are now out of balance
}

namespace {

// The settling box made periodic along x (no walls across x: a floor, a lid and two side planes),
// with gravity tilted along x so that the grains drift through the faces: the cuts along x meet
// across the face too (the first rank's grains touch the last's), and with one rank its own images
// carry the pairs across.
std::string periodic_channel() {
  std::string s = settling_box(300, 6, 100.0);
  const std::string box = s.substr(s.find("[[wall]]"), s.find("[[fill]]") - s.find("[[wall]]"));
  std::ostringstream walls;
  for (const char* w : {"point = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]", "point = [0.0, 0.02, 0.0]\nnormal = [0.0, -1.0, 0.0]",
                        "point = [0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]", "point = [0.0, 0.0, 0.02]\nnormal = [0.0, 0.0, -1.0]"})
    walls << "[[wall]]\ntype = \"plane\"\n" << w << "\n";
  walls << "[periodic]\nx = [0.0, 0.04]\n";
  s.replace(s.find(box), box.size(), walls.str());
  const std::string from = "gravity = [0.0, -100", to = "gravity = [30.0, -100";
  s.replace(s.find(from), from.size(), to);
  return s;
}

}  // namespace

TEST_CASE("a periodic channel on several ranks tracks the same channel on one", "[mpi][rank_step][periodic]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  const std::string scene = periodic_channel();
  gf::DemSimulation one = gf::DemSimulation::from_text(scene);
  gf::RankSimulation many = gf::RankSimulation::from_text(scene, mpi);
  const auto n = static_cast<std::int64_t>(one.grains().n_owned);
  REQUIRE(many.total_grains() == n);
  // Thrown about, so that grains cross the periodic faces and the cuts while their contacts hold springs.
  stir_owned(one.grains(), 0.5);
  stir_owned(many.grains(), 0.5);

  const auto [worst_e, worst_p] = track(one, many, "periodic channel");
  // Grains past the faces: on one rank the list holds images, on several the ghost rows include
  // copies across the faces; wrapped at each rebuild, every grain stays within the periodic box
  // give or take the half skin (0.075 mm) it may move between rebuilds.
  const gf::Grains& g = many.grains();
  std::int64_t outside = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) outside += g.pos.x[i] < -7.5e-5 || g.pos.x[i] >= 0.04 + 7.5e-5;
  const gf::RankCounters& c = many.counters();
  const std::int64_t migrated = mpi.sum(c.migrated), ghosts = mpi.sum(c.ghosts);
  const double px = totals_ranks(many).momentum[0];
  if (mpi.rank() == 0)
    std::cout << "periodic channel: " << n << " grains, " << c.rebuilds << " rebuilds, " << migrated << " rows migrated, "
              << ghosts << " ghost rows now, x momentum " << px << " kg m/s; largest relative kinetic-energy difference "
              << worst_e << ", momentum difference " << worst_p << " of sum m|v|\n";
  CHECK(one.world().resources.get<gf::PeriodicImages>().size() > 0);
  CHECK(mpi.sum(outside) == 0);
  CHECK(migrated > 0);
  CHECK(ghosts > 0);
  CHECK(worst_e < 1e-8);
  CHECK(worst_p < 1e-8);
}
