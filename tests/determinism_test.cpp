// Determinism: the order of rows in the Grains table changes nothing, and runs with the same thread
// count, or with 1 and 2 threads, give the same bits. Both follow from the design: rows are re-sorted
// by (cell, id) at every neighbour-list rebuild, and pair forces are summed without atomics in an
// order set by the row count alone (contact order within fixed slabs of owner rows, the shares that
// fall in a later slab added there in slab order; pair_contact.hpp), so neither the input order nor
// the thread schedule can reach the arithmetic.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include "systems/broadphase/broadphase.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Grains;
using gf::test::stir_by_id;
using gf::test::State;
using gf::test::state_by_id;

namespace {

// `small` grains of 2 mm and `large` of 3 mm poured at ~29 % solid fraction into a closed box of
// edge `side` (SI units). dt = 2e-5 s is 0.06 of the critical (tangential small-small) period.
std::string box_scene(int small, int large, double side) {
  std::ostringstream s;
  s.precision(17);
  s << "[run]\ndt = 2.0e-5\nduration = 1.0\nskin = 2.0e-4\ngravity = [0.0, -9.81, 0.0]\nseed = 17\n"
    << "[[species]]\nname = \"small\"\ndiameter = 2.0e-3\ndensity = 2500.0\n"
    << "[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
    << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
    << "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [" << side << ", " << 1.5 * side << ", " << side
    << "]\n"
    << "[[fill]]\nkind = \"random\"\n"
    << "region = { shape = \"box\", lo = [0.0015, 0.0015, 0.0015], hi = [" << side - 0.0015 << ", "
    << 1.5 * side - 0.0015 << ", " << side - 0.0015 << "] }\n"
    << "count = { small = " << small << ", large = " << large << " }\n";
  return s.str();
}

struct Difference {
  std::size_t grains = 0;   // grains with any differing component
  double largest = 0.0;     // largest |difference| of a position component, m
  std::string first;        // the first one, for the message
};

Difference compare(const State& a, const State& b) {
  Difference d;
  REQUIRE(a.size() == b.size());
  const char* names[9] = {"x", "y", "z", "vx", "vy", "vz", "wx", "wy", "wz"};
  for (std::size_t id = 0; id < a.size(); ++id) {
    if (a[id] == b[id]) continue;
    ++d.grains;
    for (int c = 0; c < 9; ++c) {
      if (a[id][c] == b[id][c]) continue;
      const double va = std::bit_cast<double>(a[id][c]), vb = std::bit_cast<double>(b[id][c]);
      if (c < 3) d.largest = std::max(d.largest, std::abs(va - vb));
      if (d.first.empty()) {
        std::ostringstream os;
        os.precision(17);
        os << "id " << id << " " << names[c] << ": " << va << " vs " << vb;
        d.first = os.str();
      }
    }
  }
  return d;
}

// Builds the scene, stirs it, optionally permutes the rows (after the world is built, before the
// priming pass that makes the first neighbour list), runs `steps` steps and returns the state.
struct RunResult {
  State state;
  std::int64_t rebuilds = 0;
  std::size_t grains = 0;
};

RunResult run(const std::string& scene, int steps, std::uint64_t permutation_seed = 0) {
  DemSimulation sim = DemSimulation::from_text(scene);
  Grains& g = sim.grains();
  // A pour from rest barely collides within a few hundred steps, so every grain also gets a random
  // velocity (up to 0.3 m/s a component) and spin, drawn by id so that it does not depend on rows.
  stir_by_id(g, 5);
  if (permutation_seed != 0) {
    std::vector<std::uint32_t> perm(g.n);
    std::iota(perm.begin(), perm.end(), 0u);
    std::shuffle(perm.begin(), perm.end(), std::mt19937_64(permutation_seed));
    g.permute(perm);
    // The permutation really reorders rows: the fill numbers ids in row order, so count misplaced ids.
    std::size_t moved = 0;
    for (std::size_t r = 0; r < g.n; ++r) moved += g.pid.id[r] != static_cast<std::int64_t>(r);
    REQUIRE(moved > g.n / 2);
  }
  sim.advance(steps);
  RunResult res;
  res.state = state_by_id(sim.grains());
  res.rebuilds = sim.world().resources.get<gf::BroadphaseState>().rebuilds;
  res.grains = sim.grains().n;
  return res;
}

}  // namespace

TEST_CASE("determinism: permuting rows before the first step changes nothing", "[determinism]") {
  // The first neighbour-list rebuild (in the priming pass, before any motion) sorts rows by
  // (cell, id); the grid spans the bounding box of the positions, which is the same for any order.
  // From then on both worlds hold the same rows in the same order, build the same pair list and sum
  // the same terms in the same order, so every bit must agree. A dependence on input order anywhere
  // (ties broken by row, a grid origin from row 0, an unsorted history merge) would show here.
  const std::string scene = box_scene(200, 100, 0.02);
  constexpr int kSteps = 300;
  const RunResult plain = run(scene, kSteps);
  const RunResult p1 = run(scene, kSteps, 101);
  const RunResult p2 = run(scene, kSteps, 202);
  REQUIRE(plain.grains == 300);
  CHECK(plain.rebuilds > 5);  // the stirred pack moved far enough to rebuild the list several times
  const Difference d1 = compare(plain.state, p1.state);
  const Difference d2 = compare(plain.state, p2.state);
  INFO("first permutation: " << d1.first << "; second: " << d2.first);
  CHECK(d1.grains == 0);
  CHECK(d2.grains == 0);
  CHECK(plain.rebuilds == p1.rebuilds);
}

TEST_CASE("determinism: runs with the same or another thread count are bit-identical", "[determinism]") {
  // Large enough (4000 grains, ~15000 pairs) that every parallel loop is split into several blocks,
  // so the partitioner's (scheduling-dependent) choice of blocks could show if it reached results.
  const std::string scene = box_scene(2700, 1300, 0.05);
  constexpr int kSteps = 1000;

  RunResult two_a, two_b, one_a, one_b;
  int threads_seen = 0;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    threads_seen = tbb::this_task_arena::max_concurrency();
    two_a = run(scene, kSteps);
    two_b = run(scene, kSteps);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one_a = run(scene, kSteps);
    one_b = run(scene, kSteps);
  }
  REQUIRE(two_a.grains == 4000);
  CHECK(two_a.rebuilds > 3);

  const Difference d2 = compare(two_a.state, two_b.state);
  const Difference d1 = compare(one_a.state, one_b.state);
  {
    INFO("2 threads, run a vs run b: " << d2.grains << " grains differ; " << d2.first);
    CHECK(d2.grains == 0);
  }
  {
    INFO("1 thread, run a vs run b: " << d1.grains << " grains differ; " << d1.first);
    CHECK(d1.grains == 0);
  }

  // Across thread counts too: every sum runs in an order fixed by the row count alone (slabs of
  // rows, blocks of pairs), never by the schedule.
  const Difference d12 = compare(one_a.state, two_a.state);
  INFO("1 thread vs " << threads_seen << " threads after " << kSteps << " steps: " << d12.grains << " of "
                      << two_a.grains << " grains differ, largest position difference " << d12.largest
                      << " m; first: " << d12.first);
  CHECK(threads_seen == 2);
  CHECK(d12.grains == 0);
}
