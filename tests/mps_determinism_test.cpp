// Repeatability of the liquid step (DESIGN: the same run gives the same bits): every system writes only its own
// rows, and the parallel CG reduces over fixed blocks in a fixed order, so 200 dam-break steps agree bit for
// bit between runs and between 1 and 2 threads, with either PPE solver.
#include <catch2/catch.hpp>

#include <cstring>
#include <string>

#include <tbb/global_control.h>

#include "mps_support.hpp"

using namespace gf;

namespace {
FluidNodes run(std::size_t threads, const std::string& solver) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  auto sim = LiquidSimulation::from_file(test::liquid_scene("dam_break_2d.toml"),
                                         {"liquid.solver={kind = \"" + solver + "\"}"});
  sim.advance(200);
  return sim.nodes();
}
bool same_bits(const ColumnD& a, const ColumnD& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
}  // namespace

TEST_CASE("200 dam-break steps are bit-for-bit repeatable, across runs and thread counts, with both solvers") {
  for (const std::string solver : {"eigen_cg", "parallel_cg"}) {
    CAPTURE(solver);
    const FluidNodes a = run(2, solver), b = run(2, solver), c = run(1, solver);
    CHECK(same_bits(a.x, b.x));
    CHECK(same_bits(a.y, b.y));
    CHECK(same_bits(a.p, b.p));
    CHECK(same_bits(a.x, c.x));
    CHECK(same_bits(a.v, c.v));
    CHECK(same_bits(a.p, c.p));
  }
}
