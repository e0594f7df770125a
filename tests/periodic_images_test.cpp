// Periodic boundaries: the list holds every pair within reach across periodic faces exactly once; a
// cluster that crosses a face keeps its contacts and springs (it moves as the same cluster shifted
// away from the face); a periodic box of grains conserves momentum; a periodic run resumes
// bit-identically from a checkpoint; a box too short for the grains is refused with the fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "systems/broadphase/broadphase.hpp"
#include "systems/fill/state_csv.hpp"
#include "systems/periodic/periodic_images.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

using Catch::Matchers::Contains;
using gf::test::TempDir;

namespace {

constexpr double kBox = 0.012;  // m, edge of the triply periodic box of the gas

std::string contact_block() {
  return "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
         "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n";
}

std::string species_block() {
  return "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
         "[[species]]\nname = \"large\"\ndiameter = 2.0e-3\ndensity = 2500.0\n";
}

// 125 grains, 1 and 2 mm, on a jittered 5 x 5 x 5 lattice of the box (2.4 mm apart, so none
// touch), with random velocities up to 0.3 m/s and spins: a granular gas that collides across
// every face and edge of the box.
std::filesystem::path write_gas(const TempDir& dir) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-1.5e-4, 1.5e-4), speed(-0.3, 0.3), spin(-50.0, 50.0);
  std::vector<gf::StateRow> rows;
  const double a = kBox / 5.0;
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 5; ++j)
      for (int k = 0; k < 5; ++k) {
        const auto id = static_cast<std::int64_t>(rows.size());
        gf::StateRow r{id, static_cast<std::int32_t>(id % 2), id % 2 ? 2.0e-3 : 1.0e-3,
                       {(i + 0.5) * a + jitter(rng), (j + 0.5) * a + jitter(rng), (k + 0.5) * a + jitter(rng)}, 0};
        r.v = {speed(rng), speed(rng), speed(rng)};
        r.w = {spin(rng), spin(rng), spin(rng)};
        rows.push_back(r);
      }
  const auto path = dir.path / "gas.csv";
  gf::write_state_csv(path, rows);
  return path;
}

std::string gas_scene(const std::filesystem::path& state) {
  return "[run]\ndt = 5.0e-6\nduration = 0.05\nskin = 1.5e-4\ngravity = [0.0, 0.0, 0.0]\n" + species_block() +
         contact_block() + "[periodic]\nx = [0.0, 0.012]\ny = [0.0, 0.012]\nz = [0.0, 0.012]\n" +
         "[[fill]]\nkind = \"file\"\npath = " + gf::test::quote(state.string()) +
         "\ntypes = { 0 = \"small\", 1 = \"large\" }\n";
}

std::array<double, 3> momentum(const gf::Grains& g) {
  std::array<double, 3> p{};
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    p[0] += g.mass.m[i] * g.vel.x[i];
    p[1] += g.mass.m[i] * g.vel.y[i];
    p[2] += g.mass.m[i] * g.vel.z[i];
  }
  return p;
}

// Minimum-image separation of owned rows a and b along periodic axis d.
double min_image(double d, double len) { return d - len * std::round(d / len); }

}  // namespace

TEST_CASE("periodic: every pair within reach across the faces is listed exactly once", "[periodic]") {
  TempDir dir("periodic_list");
  auto sim = gf::DemSimulation::from_text(gas_scene(write_gas(dir)));
  sim.advance(3000);  // the gas has spread across the faces
  gf::World& w = sim.world();
  gf::Grains& g = w.grains;
  auto& bp = w.resources.get<gf::BroadphaseState>();
  auto& list = w.resources.get<gf::NeighborList>();
  auto& im = w.resources.get<gf::PeriodicImages>();
  gf::rebuild_neighbors(g, bp, list, w.resources.get<gf::PairHistory>(), im);
  REQUIRE(im.size() > 0);
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> listed;
  for (std::size_t k = 0; k < list.pairs(); ++k) {
    const std::uint32_t a = list.i[k], b = gf::base_row(g, im, list.j[k]);
    REQUIRE(a < g.n_owned);
    ++listed[{std::min(a, b), std::max(a, b)}];
    // The listed rows' separation is the pair's nearest image.
    const std::size_t j = list.j[k];
    const double dx = g.pos.x[j] - g.pos.x[a], dy = g.pos.y[j] - g.pos.y[a], dz = g.pos.z[j] - g.pos.z[a];
    const double mx = min_image(g.pos.x[b] - g.pos.x[a], kBox), my = min_image(g.pos.y[b] - g.pos.y[a], kBox),
                 mz = min_image(g.pos.z[b] - g.pos.z[a], kBox);
    CHECK(std::abs(dx - mx) < 1e-12);  // round-off of one box shift (1e-17 m) with margin
    CHECK(std::abs(dy - my) < 1e-12);
    CHECK(std::abs(dz - mz) < 1e-12);
  }
  std::size_t in_reach = 0, crossing = 0;
  for (std::uint32_t a = 0; a < g.n_owned; ++a)
    for (std::uint32_t b = a + 1; b < g.n_owned; ++b) {
      const double mx = min_image(g.pos.x[b] - g.pos.x[a], kBox), my = min_image(g.pos.y[b] - g.pos.y[a], kBox),
                   mz = min_image(g.pos.z[b] - g.pos.z[a], kBox);
      const double reach = g.radius.r[a] + g.radius.r[b] + bp.skin;
      if (mx * mx + my * my + mz * mz >= reach * reach) continue;
      ++in_reach;
      const bool direct = mx == g.pos.x[b] - g.pos.x[a] && my == g.pos.y[b] - g.pos.y[a] &&
                          mz == g.pos.z[b] - g.pos.z[a];
      crossing += !direct;
      CHECK(listed[{a, b}] == 1);
    }
  for (const auto& [pair, count] : listed) CHECK(count == 1);
  INFO("pairs in reach " << in_reach << ", across a face " << crossing);
  CHECK(crossing > 5);  // the check covered pairs through images, not only direct ones
}

TEST_CASE("periodic: a periodic box of colliding grains conserves momentum", "[periodic]") {
  TempDir dir("periodic_momentum");
  auto sim = gf::DemSimulation::from_text(gas_scene(write_gas(dir)));
  const auto p0 = momentum(sim.grains());
  double scale = 0.0;  // sum of m |v|: the size of the terms the momentum is summed from
  const gf::Grains& g = sim.grains();
  for (std::size_t i = 0; i < g.n_owned; ++i) scale += g.mass.m[i] * std::hypot(g.vel.x[i], g.vel.y[i], g.vel.z[i]);
  const auto rebuilds0 = sim.world().resources.get<gf::BroadphaseState>().rebuilds;
  sim.advance(6000);
  const auto p1 = momentum(sim.grains());
  // Contact forces are equal and opposite, also through images (their share is folded into the
  // owner), so only round-off changes the momentum: 6,000 steps of sums of ~1e3 terms of relative
  // error 1e-16 stay far below 1e-11 of the scale. A dropped image force would show at ~1e-3.
  for (int d = 0; d < 3; ++d) CHECK(std::abs(p1[d] - p0[d]) < 1e-11 * scale);
  CHECK(sim.world().resources.get<gf::BroadphaseState>().rebuilds > rebuilds0 + 10);
  CHECK(sim.world().resources.get<gf::PairHistory>().size() > 0);
}

namespace {

// Three 2 mm grains stacked as a pyramid on a floor (the top grain spinning, so its contacts slide
// and their springs load), all moving along x at 0.5 m/s through a box periodic in x with
// L = 2^-5 m, starting at x0 (the bottom pair's middle).
std::string pyramid_scene(const TempDir& dir, const std::string& name, double x0) {
  const double r = 1.0e-3;
  std::vector<gf::StateRow> rows{{0, 1, 2 * r, {x0 - r, r, 0.0}, 0},
                                 {1, 1, 2 * r, {x0 + r, r, 0.0}, 0},
                                 {2, 1, 2 * r, {x0, r + std::sqrt(3.0) * r, 0.0}, 0}};
  for (auto& row : rows) row.v = {0.5, 0.0, 0.0};
  rows[2].w = {0.0, 0.0, 10.0};
  const auto path = dir.path / (name + ".csv");
  gf::write_state_csv(path, rows);
  return "[run]\ndt = 5.0e-6\nduration = 0.05\nskin = 1.5e-4\ngravity = [0.0, -9.81, 0.0]\n" + species_block() +
         contact_block() + "[periodic]\nx = [0.0, 0.03125]\n" +
         "[[wall]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n" +
         "[[fill]]\nkind = \"file\"\npath = " + gf::test::quote(path.string()) +
         "\ntypes = { 0 = \"small\", 1 = \"large\" }\n";
}

// The springs by grain pair (min id, max id), each seen from the lower id.
std::map<std::uint64_t, std::vector<double>> springs_by_pair(gf::World& w) {
  const auto& list = w.resources.get<gf::NeighborList>();
  const auto& h = w.resources.get<gf::PairHistory>();
  const gf::Grains& g = w.grains;
  std::map<std::uint64_t, std::vector<double>> out;
  for (std::size_t e = 0; e < h.size(); ++e) {
    const auto k = static_cast<std::size_t>(h.pair[e]);
    const std::int64_t a = g.pid.id[list.i[k]], b = g.pid.id[list.j[k]];
    const double sign = a < b ? 1.0 : h.exchange_sign;
    std::vector<double> v;
    for (std::size_t q = 0; q < h.width; ++q) v.push_back(sign * h.value[q][e]);
    out[list.key[k]] = v;
  }
  return out;
}

}  // namespace

TEST_CASE("periodic: a cluster crossing a face keeps its contacts and springs", "[periodic]") {
  TempDir dir("periodic_cross");
  const double len = 0.03125;
  // The same cluster, once starting 4 mm before the face and once half a box away from it (both
  // x0 are exact binary fractions, so the starts differ by exactly L/2).
  auto crossing = gf::DemSimulation::from_text(pyramid_scene(dir, "a", len - 0.00390625));
  auto away = gf::DemSimulation::from_text(pyramid_scene(dir, "b", len / 2 - 0.00390625));
  // 3,000 steps of 5e-6 s: the cluster travels about 7 mm, across the face after about 4 mm.
  // Steps in which a loaded spring belongs to a pair listed through an image (across the face):
  int through_image = 0;
  for (int k = 0; k < 3000; ++k) {
    crossing.advance(1);
    away.advance(1);
    const auto& list = crossing.world().resources.get<gf::NeighborList>();
    const auto& h = crossing.world().resources.get<gf::PairHistory>();
    for (std::size_t e = 0; e < h.size(); ++e)
      if (list.j[static_cast<std::size_t>(h.pair[e])] >= crossing.grains().n_owned && h.value[0][e] != 0.0) {
        ++through_image;
        break;
      }
  }
  INFO("steps with a loaded spring through an image: " << through_image);
  CHECK(through_image > 50);  // 416 steps in this build: the springs crossed loaded
  const gf::Grains& a = crossing.grains();
  const gf::Grains& b = away.grains();
  bool wrapped = false;
  for (std::size_t i = 0; i < a.n_owned; ++i) wrapped = wrapped || a.pos.x[i] < len / 2;
  REQUIRE(wrapped);  // some grain went through the face and was wrapped
  // By id: the crossing run's positions shifted by L/2 (modulo L) and its velocities and spins equal
  // the other run's. The two runs differ only in round-off (coordinates of other magnitudes), which
  // three grains in steady contact do not amplify: 1e-12 m and 1e-9 m/s leave room for it, while
  // a spring lost at the face would change the top grain's motion by ~1e-3 m/s within the run.
  auto row_of = [](const gf::Grains& g, std::int64_t id) {
    for (std::size_t i = 0; i < g.n_owned; ++i)
      if (g.pid.id[i] == id) return i;
    return std::size_t(-1);
  };
  for (std::int64_t id = 0; id < 3; ++id) {
    const std::size_t i = row_of(a, id), j = row_of(b, id);
    REQUIRE(i < a.n_owned);
    REQUIRE(j < b.n_owned);
    CHECK(std::abs(min_image(a.pos.x[i] - b.pos.x[j] - len / 2, len)) < 1e-12);
    CHECK(std::abs(a.pos.y[i] - b.pos.y[j]) < 1e-12);
    CHECK(std::abs(a.vel.x[i] - b.vel.x[j]) < 1e-9);
    CHECK(std::abs(a.vel.y[i] - b.vel.y[j]) < 1e-9);
    CHECK(std::abs(a.omega.z[i] - b.omega.z[j]) < 1e-6);  // rad/s: spins of ~10 rad/s
  }
  const auto sa = springs_by_pair(crossing.world()), sb = springs_by_pair(away.world());
  REQUIRE(sb.size() >= 1);  // the top grain on each bottom grain
  REQUIRE(sa.size() == sb.size());
  double loaded = 0.0;
  for (const auto& [key, v] : sb) {
    REQUIRE(sa.count(key) == 1);
    for (std::size_t q = 0; q < v.size(); ++q) {
      CHECK(std::abs(sa.at(key)[q] - v[q]) < 1e-12 + 1e-6 * std::abs(v[q]));
      loaded = std::max(loaded, std::abs(v[q]));
    }
  }
  CHECK(loaded > 1e-7);  // the springs carried were loaded (m or rad), not zero
}

TEST_CASE("periodic: a periodic run resumes bit-identically from a checkpoint", "[periodic][checkpoint]") {
  TempDir dir("periodic_ckpt");
  const std::string scene = gas_scene(write_gas(dir));
  auto whole = gf::DemSimulation::from_text(scene);
  whole.advance(3000);
  auto first = gf::DemSimulation::from_text(scene);
  first.advance(1700);
  REQUIRE(first.grains().n > first.grains().n_owned);  // images present at the checkpoint
  gf::CheckpointWriter w;
  gf::save_dem_state(w, first.world(), first.scene());
  w.write(dir.path / "c.gfc");
  auto resumed = gf::DemSimulation::from_text(scene);
  resumed.resume(gf::CheckpointReader(dir.path / "c.gfc"));
  resumed.advance(1300);
  const gf::Grains& a = whole.grains();
  const gf::Grains& b = resumed.grains();
  REQUIRE(a.n == b.n);
  REQUIRE(a.n_owned == b.n_owned);
  CHECK(std::memcmp(a.pos.x.data(), b.pos.x.data(), a.n * sizeof(double)) == 0);
  CHECK(std::memcmp(a.vel.y.data(), b.vel.y.data(), a.n * sizeof(double)) == 0);
  CHECK(std::memcmp(a.omega.z.data(), b.omega.z.data(), a.n * sizeof(double)) == 0);
  CHECK(whole.world().resources.get<gf::BroadphaseState>().rebuilds ==
        resumed.world().resources.get<gf::BroadphaseState>().rebuilds);

  // The same checkpoint is refused by the scene without periodic faces, naming the fix.
  std::string flat = scene;
  flat.replace(flat.find("[periodic]"), std::string("[periodic]\nx = [0.0, 0.012]\ny = [0.0, 0.012]\nz = [0.0, 0.012]\n").size(), "");
  auto other = gf::DemSimulation::from_text(flat);
  CHECK_THROWS_WITH(other.resume(gf::CheckpointReader(dir.path / "c.gfc")), Contains("[periodic]"));
}

TEST_CASE("periodic: a box too short for the grains, or a table without axes, is refused with the fix",
          "[periodic][scene]") {
  TempDir dir("periodic_scene");
  std::string scene = gas_scene(write_gas(dir));
  const std::string box = "x = [0.0, 0.012]\n";
  std::string shortbox = scene;
  shortbox.replace(shortbox.find(box), box.size(), "x = [0.0, 0.004]\n");
  CHECK_THROWS_WITH(gf::DemSimulation::from_text(shortbox), Contains("x") && Contains("shorter than") &&
                                                                 Contains("lengthen the box"));
  std::string empty = scene;
  const std::string axes = "[periodic]\nx = [0.0, 0.012]\ny = [0.0, 0.012]\nz = [0.0, 0.012]\n";
  empty.replace(empty.find(axes), axes.size(), "[periodic]\n");
  CHECK_THROWS_WITH(gf::DemSimulation::from_text(empty), Contains("names no axis"));
  std::string reversed = scene;
  reversed.replace(reversed.find(box), box.size(), "x = [0.012, 0.0]\n");
  CHECK_THROWS_WITH(gf::DemSimulation::from_text(reversed), Contains("max > min"));
}
