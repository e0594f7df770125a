// Broadphase: the Verlet list built from the cell grid holds exactly the pairs a brute-force search
// finds, rows come out re-sorted by (cell, id) with every column moved along and cells ordered
// fastest along the shortest extent, a non-finite position is an error naming the row, the list is
// rebuilt exactly when some row moved more than skin/2 and holds every touching pair in between,
// contact history (tangential spring, rolling angle) survives rebuilds and the re-sorting of rows,
// and grains queued for insertion or removal join or leave at the next rebuild with every other
// spring kept.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "engine/grains.hpp"
#include "engine/world.hpp"
#include "engine/machine_memory.hpp"
#include "engine/run_loop.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/walls/walls.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

using gf::BroadphaseState;
using gf::Grains;
using gf::NeighborList;
using gf::PairHistory;
using gf::test::stir_by_id;
using gf::test::TempDir;
namespace fs = std::filesystem;

namespace {

// ---------------------------------------------------------------------------------------------------------------------
// Packs and the brute-force reference.

struct Pack {
  std::vector<double> x, y, z, r;
  std::vector<std::int64_t> id;
  std::size_t size() const { return x.size(); }
  void add(double a, double b, double c, double rad) {
    id.push_back(static_cast<std::int64_t>(x.size()));
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
    r.push_back(rad);
  }
  // Ids in random order, so that "ties by id" differs from "ties by input row".
  void shuffle_ids(std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::shuffle(id.begin(), id.end(), rng);
  }
};

// n spheres with radii uniform in [rmin, 3 rmin] (a spread of x3), centres uniform in the cube [0, side]^3.
// Overlaps are allowed: the broadphase must not care.
Pack random_pack(std::uint64_t seed, std::size_t n, double side, double rmin) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, side), ur(rmin, 3.0 * rmin);
  Pack p;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = u(rng), b = u(rng), c = u(rng);
    p.add(a, b, c, ur(rng));
  }
  p.shuffle_ids(seed + 1000);
  return p;
}

// Every pair closer than r_i + r_j + skin, as unordered id pairs. The test expression is the
// broadphase's own (difference of coordinates squared, (r_i + r_j) + skin squared, strict <): both
// are symmetric in i and j bit for bit, so even a pair exactly at the cut-off is classified the same
// way by both and the sets must be identical, not merely close.
std::set<std::uint64_t> brute_force_pairs(const Pack& p, double skin) {
  std::set<std::uint64_t> out;
  for (std::size_t a = 0; a < p.size(); ++a)
    for (std::size_t b = a + 1; b < p.size(); ++b) {
      const double dx = p.x[b] - p.x[a], dy = p.y[b] - p.y[a], dz = p.z[b] - p.z[a];
      const double cut = p.r[a] + p.r[b] + skin;
      if (dx * dx + dy * dy + dz * dz < cut * cut) out.insert(gf::pair_key(p.id[a], p.id[b]));
    }
  return out;
}

// Fills a Grains table from a pack; every other column gets a value derived from the id, so that a
// row that is re-sorted without one of its columns is caught.
void load(Grains& g, const Pack& p) {
  g.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double k = static_cast<double>(p.id[i]);
    g.pos.x[i] = p.x[i];
    g.pos.y[i] = p.y[i];
    g.pos.z[i] = p.z[i];
    g.radius.r[i] = p.r[i];
    g.pid.id[i] = p.id[i];
    g.vel.x[i] = k + 0.1;
    g.vel.y[i] = k + 0.2;
    g.vel.z[i] = k + 0.3;
    g.omega.x[i] = -k;
    g.omega.y[i] = -k - 0.5;
    g.omega.z[i] = -k - 0.25;
    g.force.x[i] = 2 * k;
    g.force.y[i] = 3 * k;
    g.force.z[i] = 4 * k;
    g.torque.x[i] = 5 * k;
    g.torque.y[i] = 6 * k;
    g.torque.z[i] = 7 * k;
    g.wall_force.x[i] = 8 * k;
    g.wall_force.y[i] = 9 * k;
    g.wall_force.z[i] = 10 * k;
    g.wall_torque.x[i] = 11 * k;
    g.wall_torque.y[i] = 12 * k;
    g.wall_torque.z[i] = 13 * k;
    g.mass.m[i] = 1 + k;
    g.mass.inv_m[i] = 1 / (1 + k);
    g.mass.inv_inertia[i] = 14 * k;
    g.species.type[i] = static_cast<std::int32_t>(p.id[i] % 3);
  }
}

// An attached component, to check that extras move with the rows too.
struct Tag {
  gf::ColumnD v;
  auto columns() { return std::tie(v); }
};

struct Built {
  Grains g;
  BroadphaseState state;
  NeighborList list;
  PairHistory history;
};

void build_list(Built& b, const Pack& p, double skin) {
  load(b.g, p);
  Tag& tag = b.g.extras.attach<Tag>(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) tag.v[i] = 100.0 + static_cast<double>(p.id[i]);
  b.state.skin = skin;
  gf::rebuild_neighbors(b.g, b.state, b.list, b.history);
}

// The list as unordered id pairs, checking its internal consistency on the way.
std::set<std::uint64_t> list_pairs(const Built& b) {
  const Grains& g = b.g;
  const NeighborList& l = b.list;
  std::set<std::uint64_t> out;
  REQUIRE(l.offsets.size() == g.n_owned + 1);
  REQUIRE(l.offsets.front() == 0);
  REQUIRE(l.offsets.back() == l.pairs());
  REQUIRE(l.i.size() == l.pairs());
  REQUIRE(l.key.size() == l.pairs());
  for (std::size_t r = 0; r < g.n_owned; ++r) {
    REQUIRE(l.offsets[r] <= l.offsets[r + 1]);
    for (std::uint32_t k = l.offsets[r]; k < l.offsets[r + 1]; ++k) {
      REQUIRE(l.i[k] == r);
      REQUIRE(l.j[k] > r);  // half list: the lower row owns the pair
      REQUIRE(l.j[k] < g.n);
      REQUIRE(l.key[k] == gf::pair_key(g.pid.id[l.i[k]], g.pid.id[l.j[k]]));
      out.insert(l.key[k]);
    }
  }
  REQUIRE(out.size() == l.pairs());  // no pair twice
  // Carried springs are packed in list order, one per list pair at most.
  REQUIRE(b.history.size() <= l.pairs());
  for (std::size_t e = 0; e < b.history.size(); ++e) {
    REQUIRE(static_cast<std::size_t>(b.history.pair[e]) < l.pairs());
    if (e > 0) REQUIRE(b.history.pair[e - 1] < b.history.pair[e]);
  }
  return out;
}


// Rows in (cell, id) order, each row's cell the one its position lies in, and every column
// (core and attached) still describing the same particle.
void check_sorted_rows(const Built& b, const Pack& p) {
  const Grains& g = b.g;
  const gf::CellGrid& grid = b.state.grid;
  REQUIRE(g.n == p.size());
  REQUIRE(grid.cell_of.size() == g.n);
  std::map<std::int64_t, std::size_t> source;
  for (std::size_t i = 0; i < p.size(); ++i) source[p.id[i]] = i;
  Grains& gm = const_cast<Grains&>(g);
  const Tag& tag = gm.extras.get<Tag>();
  for (std::size_t r = 0; r < g.n; ++r) {
    INFO("row " << r << ", id " << g.pid.id[r]);
    REQUIRE(source.count(g.pid.id[r]) == 1);
    const std::size_t s = source[g.pid.id[r]];
    const double k = static_cast<double>(p.id[s]);
    REQUIRE(g.pos.x[r] == p.x[s]);
    REQUIRE(g.pos.y[r] == p.y[s]);
    REQUIRE(g.pos.z[r] == p.z[s]);
    REQUIRE(g.radius.r[r] == p.r[s]);
    REQUIRE(g.vel.z[r] == k + 0.3);
    REQUIRE(g.omega.y[r] == -k - 0.5);
    REQUIRE(g.force.y[r] == 3 * k);
    REQUIRE(g.torque.z[r] == 7 * k);
    REQUIRE(g.wall_force.x[r] == 8 * k);
    REQUIRE(g.wall_torque.z[r] == 13 * k);
    REQUIRE(g.mass.m[r] == 1 + k);
    REQUIRE(g.mass.inv_inertia[r] == 14 * k);
    REQUIRE(g.species.type[r] == static_cast<std::int32_t>(p.id[s] % 3));
    REQUIRE(tag.v[r] == 100.0 + k);
    // The cell recorded for the row is the one its position lies in (grid axis d runs along
    // coordinate grid.axis[d]).
    const double q[3] = {g.pos.x[r], g.pos.y[r], g.pos.z[r]};
    std::int64_t c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = std::min(static_cast<std::int64_t>((q[grid.axis[d]] - grid.origin[d]) * (1.0 / grid.cell)),
                      grid.dims[d] - 1);
    REQUIRE(grid.cell_of[r] == static_cast<std::uint32_t>((c[2] * grid.dims[1] + c[1]) * grid.dims[0] + c[0]));
    if (r > 0) {
      REQUIRE(grid.cell_of[r - 1] <= grid.cell_of[r]);
      if (grid.cell_of[r - 1] == grid.cell_of[r]) REQUIRE(g.pid.id[r - 1] < g.pid.id[r]);
    }
  }
}

void check_against_brute_force(const Pack& p, double skin, std::size_t min_pairs) {
  Built b;
  build_list(b, p, skin);
  const std::set<std::uint64_t> got = list_pairs(b);
  const std::set<std::uint64_t> want = brute_force_pairs(p, skin);
  std::vector<std::uint64_t> missing, extra;
  std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missing));
  std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
  INFO("pairs: brute force " << want.size() << ", grid " << got.size() << "; missing " << missing.size()
                             << ", extra " << extra.size() << "; grid " << b.state.grid.dims[0] << "x"
                             << b.state.grid.dims[1] << "x" << b.state.grid.dims[2] << " cells of "
                             << b.state.grid.cell);
  CHECK(missing.empty());
  CHECK(extra.empty());
  CHECK(want.size() >= min_pairs);  // the pack really tests something
  check_sorted_rows(b, p);
}

// ---------------------------------------------------------------------------------------------------------------------
// Scenes for the dynamic tests.

// A few hundred grains of 2 and 3 mm in a closed box (SI units). dt is 0.06 of the critical period.
std::string pack_scene(double skin) {
  std::ostringstream s;
  s.precision(17);
  s << R"([run]
dt = 2.0e-5
duration = 1.0
skin = )" << skin << R"(
gravity = [0.0, -9.81, 0.0]
seed = 5

[[species]]
name = "small"
diameter = 2.0e-3
density = 2500.0

[[species]]
name = "large"
diameter = 3.0e-3
density = 2500.0

[contact]
model = "linear_spring_dashpot"
kn = 1000.0
kt = 600.0
kr = 1.0e-5
en = 0.3
et = 0.3
er = 0.3
friction = 0.3
rolling_friction = 5.0e-5

[[wall]]
type = "box"
lo = [0.0, 0.0, 0.0]
hi = [0.02, 0.03, 0.02]

[[fill]]
kind = "random"
region = { shape = "box", lo = [0.0015, 0.0015, 0.0015], hi = [0.0185, 0.0285, 0.0185] }
count = { small = 200, large = 100 }
)";
  return s.str();
}

std::size_t row_of(const Grains& g, std::int64_t id) {
  for (std::size_t r = 0; r < g.n; ++r)
    if (g.pid.id[r] == id) return r;
  FAIL("no row has id " << id);
  return 0;
}

// Pair history keyed by pair, oriented from the lower id to the higher one: the law evaluates the
// spring as seen from the owner row i, so a pair owned by its higher id carries the opposite sign.
std::map<std::uint64_t, std::vector<double>> oriented_history(const Grains& g, const NeighborList& l,
                                                              PairHistory& h) {
  std::map<std::uint64_t, std::vector<double>> out;
  for (std::size_t e = 0; e < h.size(); ++e) {
    const auto k = static_cast<std::size_t>(h.pair[e]);
    const double s = g.pid.id[l.i[k]] < g.pid.id[l.j[k]] ? 1.0 : -1.0;
    REQUIRE(h.width > 0);
    for (std::size_t q = 0; q < h.width; ++q) out[l.key[k]].push_back(s * h.value[q][e]);
  }
  return out;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
TEST_CASE("neighbours: grains piled far closer than a packing stop the search before the memory runs out",
          "[broadphase]") {
  // 3,000 grains of 1 to 3 mm radius inside a 1 mm cube: every pair is listed, 4.5 million of them.
  // With the memory the search may plan for lowered to 64 MB (32 MB for the list: 524,288 pairs) the
  // search stops past that bound with the reason, where it once grew until the machine ran out.
  const Pack p = random_pack(11, 3000, 0.001, 0.001);
  gf::memory_limit().store(std::size_t(64) << 20);
  Built b;
  std::string message;
  try {
    build_list(b, p, 1e-4);
  } catch (const gf::StabilityError& e) {
    message = e.what();
  }
  gf::memory_limit().store(0);
  CHECK_THAT(message, Catch::Contains("the neighbour list passed 524288 pairs") && Catch::Contains("Fix:"));
  // The same pile with the machine's own memory is listed whole (4.5 million pairs, 0.3 GB).
  Built whole;
  build_list(whole, p, 1e-4);
  CHECK(whole.list.pairs() == 3000u * 2999u / 2u);
}

TEST_CASE("broadphase: grid pairs equal brute-force pairs on random polydisperse packs", "[broadphase]") {
  // 1500 spheres of radius 0.5..1.5 mm in a 30 mm cube, skin 0.2 mm: cells of 3.2 mm, ~10^3 cells.
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    INFO("seed " << seed);
    check_against_brute_force(random_pack(seed, 1500, 0.03, 0.5e-3), 0.2e-3, 500);
  }
}

TEST_CASE("broadphase: a binary 1:3 mixture in a thin slab, searched by size class, equals brute force",
          "[broadphase]") {
  // The seed drum's mixture: radii 0.5 and 1.5 mm, one large grain in 28 (equal volumes), in a slab
  // 8 mm thick like the drum, skin 0.15 mm. The large grains form the coarse class (radius above
  // twice the smallest): small-small pairs come from the grid of all rows, small-large and
  // large-large from the large grains' own search, each pair once. Overlaps are allowed.
  for (std::uint64_t seed : {7u, 8u, 9u}) {
    INFO("seed " << seed);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 0.04), uz(0.0, 0.008);
    Pack p;
    for (std::size_t i = 0; i < 6000; ++i) p.add(u(rng), u(rng) * 0.5, uz(rng), i % 28 == 0 ? 1.5e-3 : 0.5e-3);
    p.shuffle_ids(seed + 1000);
    check_against_brute_force(p, 0.15e-3, 5000);
    Built b;
    build_list(b, p, 0.15e-3);
    CHECK(b.state.search.split());
    CHECK(b.state.search.coarse_rows() == 215u);  // ceil(6000 / 28)
    CHECK(b.state.search.fine_radius() == 0.5e-3);
  }
}

TEST_CASE("broadphase: a dense pack spanning many cells", "[broadphase]") {
  // 6000 spheres of radius 0.2..0.6 mm in a 25 mm cube: ~20^3 cells, many overlapping spheres.
  check_against_brute_force(random_pack(21, 6000, 0.025, 0.2e-3), 0.05e-3, 2000);
}

TEST_CASE("broadphase: degenerate packs", "[broadphase]") {
  SECTION("no particles") {
    Built b;
    build_list(b, Pack{}, 0.1);
    CHECK(b.list.pairs() == 0);
    CHECK(b.list.offsets == std::vector<std::uint32_t>{0});
  }
  SECTION("a single particle") {
    Pack p;
    p.add(0.1, 0.2, 0.3, 1e-3);
    Built b;
    build_list(b, p, 1e-4);
    CHECK(b.list.pairs() == 0);
    }
  SECTION("all particles in one cell") {
    // Centres within 2 mm, all radii 1.5 mm: the cell edge 2 rmin + skin exceeds the pack.
    Pack p = random_pack(31, 40, 0.002, 0.5e-3);
    for (double& r : p.r) r = 1.5e-3;
    Built b;
    build_list(b, p, 0.2e-3);
    CHECK(b.state.grid.cells() == 1);
    check_against_brute_force(p, 0.2e-3, 500);
  }
  SECTION("particles on cell faces") {
    // rmin = 0.25 and skin = 0.5 make the cell edge (2 rmin + skin) exactly 1 and the origin 0, so
    // integer coordinates are exact cell faces. A lattice of spacing 0.5 puts every other particle
    // on a face; pairs at distance 1 with both radii 0.25 sit exactly on the cut-off (excluded by
    // both), and larger radii make rows search more than one cell around their own.
    std::mt19937_64 rng(41);
    const double radii[4] = {0.25, 0.3, 0.35, 0.4};
    Pack p;
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; j <= 6; ++j)
        for (int k = 0; k <= 6; ++k) p.add(0.5 * i, 0.5 * j, 0.5 * k, radii[rng() % 4]);
    p.r[0] = 0.25;
    // A few particles one ulp either side of a face.
    p.add(std::nextafter(1.0, 0.0), 1.0, 1.0, 0.3);
    p.add(std::nextafter(2.0, 3.0), std::nextafter(1.0, 0.0), 1.5, 0.25);
    p.add(1.5, std::nextafter(2.0, 3.0), std::nextafter(2.0, 0.0), 0.35);
    p.shuffle_ids(42);
    Built b;
    build_list(b, p, 0.5);
    REQUIRE(b.state.grid.cell == 1.0);
    REQUIRE(b.state.grid.origin == std::array<double, 3>{0.0, 0.0, 0.0});
    check_against_brute_force(p, 0.5, 1000);
  }
  SECTION("two clusters far apart: the grid coarsens, pairs stay exact") {
    Pack p = random_pack(51, 300, 0.01, 0.3e-3);
    const Pack far = random_pack(52, 300, 0.01, 0.3e-3);
    for (std::size_t i = 0; i < far.size(); ++i) p.add(far.x[i] + 500.0, far.y[i] - 300.0, far.z[i] + 800.0, far.r[i]);
    p.shuffle_ids(53);
    check_against_brute_force(p, 0.1e-3, 100);
  }
}

TEST_CASE("broadphase: rows are sorted by cell with ties by id, whatever the input order", "[broadphase]") {
  // Many particles per cell, ids shuffled against input rows: the row order after a rebuild must be
  // the same for two inputs that differ only in row order.
  const Pack p = random_pack(61, 2000, 0.01, 0.3e-3);
  Pack q = p;
  std::vector<std::size_t> perm(p.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937_64(62));
  for (std::size_t i = 0; i < p.size(); ++i) {
    q.x[i] = p.x[perm[i]];
    q.y[i] = p.y[perm[i]];
    q.z[i] = p.z[perm[i]];
    q.r[i] = p.r[perm[i]];
    q.id[i] = p.id[perm[i]];
  }
  Built a, b;
  build_list(a, p, 0.1e-3);
  build_list(b, q, 0.1e-3);
  check_sorted_rows(a, p);
  check_sorted_rows(b, q);
  REQUIRE(a.g.n == b.g.n);
  for (std::size_t r = 0; r < a.g.n; ++r) REQUIRE(a.g.pid.id[r] == b.g.pid.id[r]);
  CHECK(a.list.key == b.list.key);
  CHECK(a.list.j == b.list.j);
}

TEST_CASE("broadphase: a non-finite position is an error naming the row", "[broadphase]") {
  const Pack p = random_pack(71, 500, 0.01, 0.3e-3);
  Built b;
  load(b.g, p);
  b.state.skin = 1e-4;
  b.g.pos.y[123] = std::numeric_limits<double>::quiet_NaN();
  b.g.pos.x[400] = std::numeric_limits<double>::infinity();
  CHECK(gf::needs_rebuild(b.g, b.state));
  REQUIRE_THROWS_WITH(gf::rebuild_neighbors(b.g, b.state, b.list, b.history),
                      Catch::Contains("particle row 123 ") && Catch::Contains("non-finite position"));

  // The same through the system, after a valid list exists: the NaN counts as "moved too far".
  Built c;
  build_list(c, p, 1e-4);
  gf::World world;
  world.grains = std::move(c.g);
  world.resources.emplace<BroadphaseState>(std::move(c.state));
  world.resources.emplace<NeighborList>(std::move(c.list));
  world.resources.emplace<PairHistory>(std::move(c.history));
  world.grains.pos.z[77] = std::numeric_limits<double>::quiet_NaN();
  CHECK(gf::needs_rebuild(world.grains, world.resources.get<BroadphaseState>()));
  gf::Broadphase sys;
  REQUIRE_THROWS_WITH(sys.run(world, {}), Catch::Contains("particle row 77 "));
}

// 25 rows of radius 0.125 on a unit square grid (z = 3) with a skin of 0.5, not yet listed: rows
// 1 apart are not pairs of the list (listed below 0.75).
struct SquareOfRows {
  gf::World world;
  SquareOfRows() {
    Pack p;
    for (int i = 0; i < 5; ++i)
      for (int j = 0; j < 5; ++j) p.add(1.0 + i, 2.0 + j, 3.0, 0.125);
    load(world.grains, p);
    world.resources.emplace<BroadphaseState>().skin = 0.5;
    world.resources.emplace<NeighborList>();
    world.resources.emplace<PairHistory>();
  }
  BroadphaseState& state() { return world.resources.get<BroadphaseState>(); }
};

TEST_CASE("broadphase: the screen fires exactly when a row moved more than skin/2", "[broadphase]") {
  // skin = 0.5 and positions on a 1/8 grid keep every displacement and its square exact.
  SquareOfRows sq;
  gf::World& world = sq.world;
  BroadphaseState& s = sq.state();
  gf::Broadphase sys;
  Grains& g = world.grains;

  CHECK(gf::needs_rebuild(g, s));  // no list yet
  sys.run(world, {});
  REQUIRE(s.rebuilds == 1);
  REQUIRE(s.valid);
  CHECK_FALSE(gf::needs_rebuild(g, s));

  const std::size_t r = 7;
  const double x0 = g.pos.x[r], y0 = g.pos.y[r], z0 = g.pos.z[r];
  SECTION("0.49 skin: no rebuild") {
    g.pos.x[r] = x0 + 0.49 * 0.5;
    CHECK_FALSE(gf::needs_rebuild(g, s));
    sys.run(world, {});
    CHECK(s.rebuilds == 1);
    CHECK(s.checks == 2);
  }
  SECTION("exactly skin/2: no rebuild (the bound is inclusive)") {
    g.pos.y[r] = y0 - 0.25;
    CHECK_FALSE(gf::needs_rebuild(g, s));
  }
  SECTION("one ulp beyond skin/2: the screen fires, and the list is kept while no missing pair touches") {
    g.pos.x[r] = std::nextafter(x0 + 0.25, 100.0);
    CHECK(gf::needs_rebuild(g, s));
    sys.run(world, {});
    CHECK(s.rebuilds == 1);
    CHECK(s.cover.kept == 1);
    s.force_rebuild = true;
    sys.run(world, {});
    CHECK(s.rebuilds == 2);
    CHECK_FALSE(gf::needs_rebuild(g, s));  // reference positions were refreshed
  }
  SECTION("the distance is Euclidean, not per axis") {
    g.pos.x[r] = x0 + 0.15;
    g.pos.y[r] = y0 + 0.15;
    CHECK_FALSE(gf::needs_rebuild(g, s));  // |d| = 0.212 < 0.25
    g.pos.z[r] = z0 + 0.15;
    CHECK(gf::needs_rebuild(g, s));  // |d| = 0.26 > 0.25
  }
  SECTION("small moves of every row do not accumulate into a rebuild") {
    for (std::size_t q = 0; q < g.n; ++q) g.pos.x[q] += 0.125;
    for (int k = 0; k < 5; ++k) sys.run(world, {});
    CHECK(s.rebuilds == 1);
    CHECK(s.checks == 6);
  }
  SECTION("the last row is checked too") {
    g.pos.z[g.n - 1] += 0.375;
    CHECK(gf::needs_rebuild(g, s));
  }
  SECTION("force_rebuild is honoured once") {
    g.pos.x[r] = x0 + 0.375;  // past skin/2: the list would be kept but for the flag

    s.force_rebuild = true;
    sys.run(world, {});
    CHECK(s.rebuilds == 2);
    CHECK_FALSE(s.force_rebuild);
    sys.run(world, {});
    CHECK(s.rebuilds == 2);
  }
}


TEST_CASE("broadphase: past skin/2 the list is rebuilt exactly when a pair missing from it touches",
          "[broadphase]") {
  // Rows 1 apart (radius 0.125, skin 0.5: listed below 0.75 apart, so neighbours are not listed).
  // Two neighbours moving towards each other by 0.4 each (D = 0.4: both are movers, d > skin - D)
  // touch (0.2 apart < 0.25) without being listed: rebuild. The same moves in one direction keep
  // them apart: no rebuild. A move of skin or more rebuilds whatever it touches.
  SquareOfRows sq;
  gf::World& world = sq.world;
  BroadphaseState& s = sq.state();
  gf::Broadphase sys;
  Grains& g = world.grains;
  sys.run(world, {});
  REQUIRE(s.rebuilds == 1);
  REQUIRE(world.resources.get<NeighborList>().pairs() == 0);
  // Row a and its neighbour b one to the right (+x), found by position after the re-sort.
  auto row_at = [&](double x, double y) {
    for (std::size_t q = 0; q < g.n; ++q)
      if (g.pos.x[q] == x && g.pos.y[q] == y) return q;
    FAIL("no row at " << x << ", " << y);
    return std::size_t(0);
  };
  const std::size_t a = row_at(2.0, 4.0), b = row_at(3.0, 4.0);
  SECTION("towards each other: they touch, missing from the list: rebuild") {
    g.pos.x[a] += 0.4;
    g.pos.x[b] -= 0.4;
    sys.run(world, {});
    CHECK(s.rebuilds == 2);
    CHECK(world.resources.get<NeighborList>().pairs() == 1);
  }
  SECTION("side by side: apart, nothing missing touches: kept") {
    g.pos.x[a] += 0.4;
    g.pos.x[b] += 0.4;
    sys.run(world, {});
    CHECK(s.rebuilds == 1);
    CHECK(s.cover.kept == 1);
  }
  SECTION("one row alone moves by the skin: rebuild") {
    g.pos.y[a] += 0.5;
    sys.run(world, {});
    CHECK(s.rebuilds == 2);
  }
}

TEST_CASE("broadphase: between rebuilds the list holds every touching pair", "[broadphase]") {
  // The promise: a pair touching now was within r_i + r_j + skin at the last rebuild, or the list
  // has just been rebuilt, both under the skin/2 screen and where the list was kept past it (a
  // missing pair can only touch if both its rows moved more than skin - D). Checked against brute
  // force after every step of a stirred pack.
  gf::DemSimulation sim = gf::DemSimulation::from_text(pack_scene(2.0e-4));
  stir_by_id(sim.grains(), 3);  // random velocities and spins, so that grains collide at once
  sim.prime();
  const auto& state = sim.world().resources.get<BroadphaseState>();
  std::size_t touching_seen = 0;
  for (int step = 0; step < 300; ++step) {
    sim.advance(1);
    const Grains& g = sim.grains();
    const NeighborList& l = sim.world().resources.get<NeighborList>();
    std::set<std::uint64_t> listed(l.key.begin(), l.key.end());
    for (std::size_t a = 0; a < g.n; ++a)
      for (std::size_t b = a + 1; b < g.n; ++b) {
        const double dx = g.pos.x[b] - g.pos.x[a], dy = g.pos.y[b] - g.pos.y[a], dz = g.pos.z[b] - g.pos.z[a];
        const double rs = g.radius.r[a] + g.radius.r[b];
        if (dx * dx + dy * dy + dz * dz < rs * rs) {
          ++touching_seen;
          INFO("step " << step << ": ids " << g.pid.id[a] << " and " << g.pid.id[b] << " touch but are not listed");
          REQUIRE(listed.count(gf::pair_key(g.pid.id[a], g.pid.id[b])) == 1);
        }
      }
  }
  INFO("rebuilds " << state.rebuilds << " in " << state.checks << " checks");
  CHECK(touching_seen > 1000);            // contacts happened
  CHECK(state.rebuilds > 5);              // the list was rebuilt on the way ...
  CHECK(state.rebuilds < state.checks);   // ... but not every step
  CHECK(state.cover.kept > 0);            // and kept past skin/2 where no missing pair touched
}

// ---------------------------------------------------------------------------------------------------------------------
// Contact history through rebuilds and re-sorting.

namespace {

// Two spheres A (id 0) and B (id 1) of radius 1 mm squeezed between two frictionless walls normal to
// x, sliding past each other along y (A at 0.15 m/s, B at 0.05 m/s) with pair friction; a third sphere
// C (id 2) rests 5 cells below them, touching nothing, so that the grid origin's y, and so the y cell
// faces, stay put while A and B move.
// A and B start just below the y face at 5 cells: A crosses it after ~30 steps, B later, so in a list
// rebuilt every step the pair is owned by A, then B (lower cell), then A again, while its spring is
// loaded.
struct SlidingPair {
  TempDir dir{"sliding_pair"};
  std::string scene;
  static constexpr double r = 1.0e-3, skin = 1.0e-4, cell = 2 * r + skin;
  static constexpr double overlap = 1.0e-5, wall_overlap = 1.0e-5;
  SlidingPair() {
    const double yb = 5 * cell;
    const double ax = 5 * cell + 0.5e-4, ay = yb - 5e-6;
    const double bx = ax + 2 * r - overlap, by = yb - 15e-6;
    std::ostringstream csv;
    csv.precision(17);
    csv << "id,type,diameter,x,y,z\n";
    csv << "0,1," << 2 * r << "," << ax << "," << ay << ",0\n";
    csv << "1,1," << 2 * r << "," << bx << "," << by << ",0\n";
    // C sits between the walls (clear of both) at the lowest y, so it fixes the origin's y; A has
    // the lowest x, so A and B share the x cell column whatever the origin's x.
    csv << "2,1," << 2 * r << "," << ax + r << "," << 0.0 << ",0\n";
    const fs::path file = dir.write("pair.csv", csv.str());
    std::ostringstream s;
    s.precision(17);
    s << "[run]\ndt = 1.0e-6\nduration = 1.0\nskin = " << skin << "\ngravity = [0.0, 0.0, 0.0]\n"
      << "[[species]]\nname = \"glass\"\ndiameter = " << 2 * r << "\ndensity = 2500.0\n"
      << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
      << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
      << "[contact.wall]\nkt = 0.0\nkr = 0.0\nfriction = 0.0\nrolling_friction = 0.0\n"
      << "[[wall]]\ntype = \"plane\"\npoint = [" << ax - r + wall_overlap << ", 0, 0]\nnormal = [1, 0, 0]\n"
      << "[[wall]]\ntype = \"plane\"\npoint = [" << bx + r - wall_overlap << ", 0, 0]\nnormal = [-1, 0, 0]\n"
      << "[[fill]]\nkind = \"file\"\npath = \"" << file.string() << "\"\ntypes = { 1 = \"glass\" }\n";
    scene = s.str();
  }
  gf::DemSimulation make(const std::vector<std::string>& overrides) const {
    gf::DemSimulation sim = gf::DemSimulation::from_text(scene, overrides);
    Grains& g = sim.grains();
    // Before the first rebuild rows are in file order: row 0 is A, row 1 is B.
    g.vel.y[0] = 0.15;  // A: common 0.1 m/s plus 0.05 m/s sliding
    g.vel.y[1] = 0.05;  // B
    return sim;
  }
};

struct GrainState {
  std::array<double, 9> v;  // position, velocity, angular velocity
  bool operator==(const GrainState&) const = default;
};

std::vector<GrainState> by_id(const Grains& g) {
  std::vector<GrainState> out(g.n);
  for (std::size_t r = 0; r < g.n; ++r)
    out[static_cast<std::size_t>(g.pid.id[r])] = {{g.pos.x[r], g.pos.y[r], g.pos.z[r], g.vel.x[r], g.vel.y[r],
                                                   g.vel.z[r], g.omega.x[r], g.omega.y[r], g.omega.z[r]}};
  return out;
}

}  // namespace

TEST_CASE("broadphase: contact history survives forced rebuilds and owner changes, bit for bit", "[broadphase]") {
  // Run 1: skin 1 m, so the list is built once (one cell, rows by id, A always owns the pair).
  // Run 2: skin 0.1 mm and force_rebuild before every step, so rows are re-sorted every step and the
  // pair changes owner as A and B cross the cell face. Each grain has a single contact, so no sum
  // order differs between the runs, and the pair law is exactly antisymmetric under swapping i and j
  // (every input only changes sign, which IEEE arithmetic does exactly). So the two runs must agree
  // bit for bit: any difference means history was lost, misplaced or misoriented on a rebuild.
  const SlidingPair setup;
  constexpr int kSteps = 400;

  gf::DemSimulation once = setup.make({"run.skin=1.0"});
  gf::DemSimulation every = setup.make({});
  once.prime();
  every.prime();
  auto& bp_once = once.world().resources.get<BroadphaseState>();
  auto& bp_every = every.world().resources.get<BroadphaseState>();

  int owner_changes = 0;
  std::int64_t owner = -1;
  double max_spring = 0.0, spring_at_change = 0.0;
  int first_difference = -1;
  for (int step = 0; step < kSteps; ++step) {
    bp_every.force_rebuild = true;
    once.advance(1);
    every.advance(1);
    const NeighborList& l = every.world().resources.get<NeighborList>();
    PairHistory& h = every.world().resources.get<PairHistory>();
    const Grains& g = every.grains();
    std::size_t k = l.pairs();
    for (std::size_t q = 0; q < l.pairs(); ++q)
      if (l.key[q] == gf::pair_key(0, 1)) k = q;
    REQUIRE(k < l.pairs());  // A and B stay in contact throughout
    const std::int64_t e = h.find(k);
    REQUIRE(e >= 0);
    const double spring = std::hypot(h.value[0][e], h.value[1][e], h.value[2][e]);  // shear.x, .y, .z
    max_spring = std::max(max_spring, spring);
    const std::int64_t o = g.pid.id[l.i[k]];
    if (owner >= 0 && o != owner) {
      ++owner_changes;
      spring_at_change = std::max(spring_at_change, spring);
    }
    owner = o;
    if (first_difference < 0 && by_id(once.grains()) != by_id(every.grains())) first_difference = step;
  }
  INFO("owner changes " << owner_changes << ", largest spring at a change " << spring_at_change << " m");
  REQUIRE(bp_once.rebuilds == 1);
  REQUIRE(bp_every.rebuilds == kSteps + 1);
  REQUIRE(owner_changes >= 2);           // the re-sorting really moved the pair between owners ...
  REQUIRE(spring_at_change > 1e-9);      // ... while its spring was loaded (1e-9 m: ~1e-6 N at kt = 600)
  CHECK(first_difference == -1);

  const auto a = by_id(once.grains()), b = by_id(every.grains());
  for (std::size_t id = 0; id < a.size(); ++id)
    for (int c = 0; c < 9; ++c) {
      INFO("id " << id << " component " << c);
      CHECK(a[id].v[c] == b[id].v[c]);
    }

  // Control: the same forced-rebuild run with the history wiped at every rebuild must differ, or the
  // comparison above could not see history at all.
  gf::DemSimulation wiped = setup.make({});
  wiped.prime();
  for (int step = 0; step < kSteps; ++step) {
    wiped.world().resources.get<BroadphaseState>().force_rebuild = true;
    wiped.advance(1);
    wiped.world().resources.get<PairHistory>().clear();
  }
  CHECK(by_id(wiped.grains()) != a);
}

TEST_CASE("broadphase: rebuilding a stirred pile every step keeps every pair's history", "[broadphase]") {
  // Two identical runs of a stirred pack piling up under 100 m/s^2 (bit-identical until they differ
  // in what is tested: same scene, and results do not depend on the thread schedule). From step 800,
  // run b rebuilds its list before every step, re-sorting rows and renumbering pairs, so pairs change
  // owner as grains cross cell faces; run a rebuilds only when the skin rule asks for it.
  //
  // History is compared per pair key, oriented from the lower id to the higher one (the law keeps it
  // as seen from the owner row). In the first step both runs evaluate every pair from identical inputs
  // (up to an exact sign change when the owner changed). The law is antisymmetric under that swap up
  // to the rounding of contracted multiply-adds (fma(li, wi, lj wj) against fma(lj, wj, li wi)), so
  // history agrees to rounding: 1e-14 of the largest spring (measured 4e-15 of the largest, 9e-15 of
  // that spring itself, since the tangential velocity v - (v.n) n is a difference of larger terms and
  // amplifies the contracted multiply-adds' rounding; 1e-17 before the geometry stage and the law
  // became separate inline functions, which changed what the compiler contracts), and forces
  // differ by that and the order of each grain's sum: |dF| <= (terms) eps sum|f| <= 1e-14 sum|f| for
  // the <= ~20 contacts of a grain. Later steps start from those rounding differences and grow them
  // through the dynamics (measured: 2e-14 of the largest spring after 50 steps); 1e-12 of the largest
  // spring and 1e-12 of the box size for positions leave a margin of ~50, while a spring carried over
  // with the wrong orientation differs by its own size (measured 1e-5 m against springs of 4e-5 m).
  constexpr int kBefore = 800, kSteps = 50;
  const std::vector<std::string> strong_gravity{"run.gravity=[0, -100, 0]"};
  gf::DemSimulation a = gf::DemSimulation::from_text(pack_scene(2.0e-4), strong_gravity);
  gf::DemSimulation b = gf::DemSimulation::from_text(pack_scene(2.0e-4), strong_gravity);
  stir_by_id(a.grains(), 9);
  stir_by_id(b.grains(), 9);
  a.advance(kBefore);
  b.advance(kBefore);
  REQUIRE(by_id(a.grains()) == by_id(b.grains()));

  auto& sb = b.world().resources.get<BroadphaseState>();
  const std::int64_t rebuilds_before = sb.rebuilds;
  std::size_t turned = 0, loaded_min = std::numeric_limits<std::size_t>::max();
  double worst_spring = 0.0, worst_position = 0.0;
  for (int step = 0; step < kSteps; ++step) {
    std::map<std::uint64_t, std::int64_t> owner_before;
    {
      const NeighborList& l = b.world().resources.get<NeighborList>();
      for (std::size_t k = 0; k < l.pairs(); ++k) owner_before[l.key[k]] = b.grains().pid.id[l.i[k]];
    }
    sb.force_rebuild = true;
    a.advance(1);
    b.advance(1);
    const NeighborList& la = a.world().resources.get<NeighborList>();
    const NeighborList& lb = b.world().resources.get<NeighborList>();
    const auto ha = oriented_history(a.grains(), la, a.world().resources.get<PairHistory>());
    const auto hb = oriented_history(b.grains(), lb, b.world().resources.get<PairHistory>());

    double largest = 0.0;
    std::size_t loaded = 0;
    for (const auto& [key, va] : ha) {
      const bool active = std::any_of(va.begin(), va.end(), [](double v) { return v != 0.0; });
      if (!active) continue;
      ++loaded;
      for (double v : va) largest = std::max(largest, std::abs(v));
    }
    loaded_min = std::min(loaded_min, loaded);
    for (std::size_t k = 0; k < lb.pairs(); ++k) {
      auto it = owner_before.find(lb.key[k]);
      const auto hit = hb.find(lb.key[k]);
      if (hit == hb.end()) continue;  // no spring: apart
      const auto& vb = hit->second;
      const bool active = std::any_of(vb.begin(), vb.end(), [](double v) { return v != 0.0; });
      if (active && it != owner_before.end() && it->second != b.grains().pid.id[lb.i[k]]) ++turned;
    }
    for (const auto& [key, va] : ha) {
      const bool active = std::any_of(va.begin(), va.end(), [](double v) { return v != 0.0; });
      auto it = hb.find(key);
      INFO("step " << step << ", pair " << (key >> 32) << "-" << (key & 0xffffffffu));
      if (!active) {
        if (it != hb.end()) {
          for (int c = 0; c < 6; ++c) REQUIRE(std::abs(it->second[c]) <= 1e-12 * largest);
        }
        continue;
      }
      REQUIRE(it != hb.end());  // a loaded spring is never dropped by a rebuild
      for (int c = 0; c < 6; ++c) {
        const double d = std::abs(va[c] - it->second[c]);
        worst_spring = std::max(worst_spring, d / largest);
        INFO("d / largest " << d / largest << ", d / own " << d / std::max(std::abs(va[c]), 1e-300));
        REQUIRE(d <= (step == 0 ? 1e-14 : 1e-12) * largest);
      }
    }

    const Grains& ga = a.grains();
    const Grains& gb = b.grains();
    if (step == 0) {
      const gf::PairForces& pfa = a.world().resources.get<gf::PairForces>();
      std::vector<double> scale(ga.n, 0.0), floor(ga.n, 0.0);
      // The overlap r_i + r_j - |x_j - x_i| of a grazing contact is a difference of numbers ~3 mm
      // apart by ~1 um: a one-ulp change in the distance (the SIMD kernel and its scalar tail
      // round it differently, and a pair may fall in either after re-sorting) moves the normal
      // force by kn (r_i + r_j) eps, a relative 4e-13 for a 0.7 um overlap (measured: one
      // contact of 0.7 um, 3.1e-16 N apart). So each contact also allows 8 such ulps.
      const double ulp_force = 8.0 * std::numeric_limits<double>::epsilon() * 1000.0 * 3.0e-3;  // kn (r_i + r_j)max
      for (std::size_t k = 0; k < la.pairs(); ++k) {
        const gf::V3<double> f = pfa.force_of(a.world().resources.get<PairHistory>(), k);  // zero when apart
        const double m = std::abs(f.x) + std::abs(f.y) + std::abs(f.z);
        scale[la.i[k]] += m;
        scale[la.j[k]] += m;
        floor[la.i[k]] += m > 0.0 ? ulp_force : 0.0;
        floor[la.j[k]] += m > 0.0 ? ulp_force : 0.0;
      }
      for (std::size_t ra = 0; ra < ga.n; ++ra) {
        const std::size_t rb = row_of(gb, ga.pid.id[ra]);
        const double tol = 1e-14 * scale[ra] + floor[ra];
        INFO("id " << ga.pid.id[ra]);
        REQUIRE(std::abs(ga.force.x[ra] - gb.force.x[rb]) <= tol);
        REQUIRE(std::abs(ga.force.y[ra] - gb.force.y[rb]) <= tol);
        REQUIRE(std::abs(ga.force.z[ra] - gb.force.z[rb]) <= tol);
      }
    }
    const auto sa = by_id(ga), sbs = by_id(gb);
    for (std::size_t id = 0; id < sa.size(); ++id)
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(sa[id].v[c] - sbs[id].v[c]);
        worst_position = std::max(worst_position, d);
        INFO("step " << step << ", id " << id);
        REQUIRE(d <= 1e-12 * 0.03);
      }
  }
  INFO("pairs that changed owner with a loaded spring: " << turned << "; fewest loaded springs " << loaded_min
                                                          << "; worst spring difference " << worst_spring
                                                          << " of the largest; worst position difference "
                                                          << worst_position << " m");
  CHECK(sb.rebuilds == rebuilds_before + kSteps);
  CHECK(loaded_min > 100);  // a pile has many loaded springs ...
  CHECK(turned >= 5);       // ... and the rebuilds moved some of them to the other particle
}

TEST_CASE("broadphase: cell order runs fastest along the shortest extent", "[broadphase]") {
  // A slab 40 x 20 x 4 cells (x, y, z): cell order runs along z, then y, then x, so cells that
  // touch across the thin axis are one cell apart in order instead of a whole 40 x 20 layer.
  std::vector<double> x, y, z;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 20; ++j)
      for (int k = 0; k < 4; ++k) {
        x.push_back((i + 0.5) * 1e-3);
        y.push_back((j + 0.5) * 1e-3);
        z.push_back((k + 0.5) * 1e-3);
      }
  gf::CellGrid grid;
  grid.build(x, y, z, 1e-3, std::size_t(1) << 24, true);
  CHECK(grid.axis == std::array<int, 3>{2, 1, 0});
  CHECK(grid.dims == std::array<std::int64_t, 3>{4, 20, 40});
  const double* coord[3] = {x.data(), y.data(), z.data()};
  for (std::size_t r = 0; r < x.size(); ++r) {
    std::int64_t c[3];
    for (int d = 0; d < 3; ++d)
      c[d] = std::min(static_cast<std::int64_t>((coord[grid.axis[d]][r] - grid.origin[d]) / grid.cell),
                      grid.dims[d] - 1);
    REQUIRE(grid.cell_of[r] == static_cast<std::uint32_t>((c[2] * grid.dims[1] + c[1]) * grid.dims[0] + c[0]));
  }
  // Without the flag the coordinate axes keep their order.
  gf::CellGrid plain;
  plain.build(x, y, z, 1e-3);
  CHECK(plain.axis == std::array<int, 3>{0, 1, 2});
  CHECK(plain.dims == std::array<std::int64_t, 3>{40, 20, 4});
}

TEST_CASE("broadphase: grains queued for insertion and removal join at the next rebuild, every other spring kept",
          "[broadphase]") {
  // Two identical stirred piles. In b one loaded grain is removed and a new grain queued in free space;
  // then both rebuild from the same positions. Every spring of a pair that does not involve the removed
  // grain must come through with its exact value (oriented by id, since the new row order may change
  // which grain owns a pair, and the carry then flips the sign exactly); the removed grain's springs
  // are gone, the new grain has none, and the wall springs of every other grain are its own.
  // Both laws: the carry knows only the history's width (6 doubles linear, 3 Hertz-Mindlin).
  const bool hertz = GENERATE(false, true);
  INFO((hertz ? "hertz_mindlin" : "linear_spring_dashpot"));
  const std::string scene = hertz ? gf::test::with_hertz_mindlin(pack_scene(2.0e-4)) : pack_scene(2.0e-4);
  // The soft Hertz material (E = 1 MPa) sinks past 0.1 d under 100 m/s^2: the limit is raised.
  const std::vector<std::string> strong_gravity{"run.gravity=[0, -100, 0]", "run.max_overlap=0.3"};
  gf::DemSimulation a = gf::DemSimulation::from_text(scene, strong_gravity);
  gf::DemSimulation b = gf::DemSimulation::from_text(scene, strong_gravity);
  stir_by_id(a.grains(), 9);
  stir_by_id(b.grains(), 9);
  a.advance(800);
  b.advance(800);
  REQUIRE(a.world().resources.get<PairHistory>().width == (hertz ? 3u : 6u));
  auto history = [](gf::DemSimulation& s) {
    return oriented_history(s.grains(), s.world().resources.get<NeighborList>(), s.world().resources.get<PairHistory>());
  };
  const auto before = history(a);
  // The grain in the most loaded springs goes.
  std::map<std::int64_t, int> springs_of;
  for (const auto& [key, v] : before) {
    ++springs_of[static_cast<std::int64_t>(key >> 32)];
    ++springs_of[static_cast<std::int64_t>(key & 0xffffffffu)];
  }
  const std::int64_t gone =
      std::max_element(springs_of.begin(), springs_of.end(), [](auto& x, auto& y) { return x.second < y.second; })->first;
  REQUIRE(springs_of[gone] >= 3);
  Grains& gb = b.grains();
  const auto spot = gf::test::free_spot(gb, {2e-3, 2e-3, 2e-3}, {18e-3, 28e-3, 18e-3}, 1e-3, 0.5e-3);
  const std::int64_t next = gb.next_id;
  gb.queue_remove(gone);
  const std::int64_t added = gb.queue_insert(gf::test::grain_at(spot, 2e-3, 2500.0, 0));
  CHECK(added == next);
  CHECK(gb.next_id == next + 1);

  for (gf::DemSimulation* s : {&a, &b})
    gf::rebuild_neighbors(s->grains(), s->world().resources.get<BroadphaseState>(),
                          s->world().resources.get<NeighborList>(), s->world().resources.get<PairHistory>());
  REQUIRE(gb.pending.empty());
  REQUIRE(gb.n == a.grains().n);
  std::set<std::int64_t> ids(gb.pid.id.begin(), gb.pid.id.end());
  CHECK(ids.size() == gb.n);  // unique
  CHECK(ids.count(gone) == 0);
  REQUIRE(ids.count(added) == 1);
  const std::size_t r_new = row_of(gb, added);
  CHECK(gb.pos.y[r_new] == spot.y);
  CHECK(gb.radius.r[r_new] == 1e-3);

  const auto ha = history(a), hb = history(b);
  std::size_t kept = 0;
  for (const auto& [key, va] : ha) {
    const auto i = static_cast<std::int64_t>(key >> 32), j = static_cast<std::int64_t>(key & 0xffffffffu);
    const auto it = hb.find(key);
    if (i == gone || j == gone) {
      CHECK(it == hb.end());
      continue;
    }
    REQUIRE(it != hb.end());
    CHECK(it->second == va);  // bit for bit
    ++kept;
  }
  CHECK(kept + static_cast<std::size_t>(springs_of[gone]) == ha.size());
  for (const auto& [key, vb] : hb) {
    const auto i = static_cast<std::int64_t>(key >> 32), j = static_cast<std::int64_t>(key & 0xffffffffu);
    CHECK(i != added);
    CHECK(j != added);
  }
  // Wall springs follow their grain; the new grain's are zero.
  Grains& ga = a.grains();
  const gf::WallHistory* wa = ga.extras.find<gf::WallHistory>();
  const gf::WallHistory* wb = gb.extras.find<gf::WallHistory>();
  REQUIRE(wa);
  REQUIRE(wb);
  std::size_t compared = 0;
  for (std::size_t r = 0; r < gb.n; ++r) {
    const std::int64_t id = gb.pid.id[r];
    for (std::size_t w = 0; w < wb->springs.size(); ++w) {
      const double* sb = wb->springs[w][r].s;
      if (id == added) {
        for (int k = 0; k < 8; ++k) CHECK(sb[k] == 0.0);
        continue;
      }
      const double* sa = wa->springs[w][row_of(ga, id)].s;
      CHECK(std::equal(sa, sa + 8, sb));
      ++compared;
    }
  }
  CHECK(compared == (gb.n - 1) * wb->springs.size());
  // The next step runs with the new table.
  REQUIRE_NOTHROW(b.advance(5));
}
