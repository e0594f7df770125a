// The pressure Poisson equation's multigrid-preconditioned CG (systems/mps/ppe_multigrid.hpp) against the
// Jacobi-preconditioned CG it may replace (ppe_parallel_cg.hpp), on the same running tanks (bench/mps_tank.hpp):
// 2D 316^2 and 3D 22^3, 46^3 fluid nodes (1e5, 1e4, 1e5). Every solve starts from p = 0 to tolerance 1e-8 and
// includes what the solver builds for it each step (the hierarchy; the compact couplings for both).
//   BM_Jacobi      Jacobi CG
//   BM_Multigrid   multigrid CG; args: sweeps, cycle (1 V, 2 W), correction scale x10, aggregate side x10 (l0)
//   BM_Setup       the hierarchy alone
// Counters: unknowns, iterations, levels.
//
// Run:  ./build/bench/ppe_multigrid_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <array>
#include <utility>

#include <benchmark/benchmark.h>

#include "bench/mps_tank.hpp"
#include "systems/mps/ppe.hpp"

namespace {

gf::LiquidSimulation& tank(int dim, int side) { return gf::bench::shared_liquid_tank(dim, side); }

struct Case {
  gf::LiquidSimulation* sim = nullptr;
  gf::PpeWorkspace ws;
  gf::LiquidParams lp;
  const gf::NeighborPairs* nb = nullptr;
};

void prepare(Case& c, const benchmark::State& state) {
  c.sim = &tank(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  c.nb = &c.sim->world().resources.get<gf::NeighborPairs>();
  c.lp = c.sim->params();
  gf::ppe_prepare(c.sim->nodes(), *c.nb, c.lp, c.sim->scene().dt, c.ws.problem);
}

void set_multigrid(Case& c, const benchmark::State& state) {
  c.lp.solver.preconditioner = gf::Preconditioner::Multigrid;
  c.lp.solver.multigrid.sweeps = static_cast<int>(state.range(2));
  c.lp.solver.multigrid.cycle = static_cast<int>(state.range(3));
  c.lp.solver.multigrid.correction = static_cast<double>(state.range(4)) / 10.0;
  c.lp.solver.multigrid.aggregate = static_cast<double>(state.range(5)) / 10.0;
}

void label(benchmark::State& state, const Case& c, const gf::PpeResult& r) {
  if (!r.converged) state.SkipWithError("did not converge");
  state.counters["unknowns"] = static_cast<double>(c.ws.problem.unknowns);
  state.counters["iterations"] = r.iterations;
  state.counters["levels"] = static_cast<double>(c.ws.multigrid.depth);
  // The coarse levels' couplings against the finest level's: the cycle's work below level 0.
  double coarse = 0;
  for (std::size_t l = 1; l < c.ws.multigrid.depth; ++l) coarse += static_cast<double>(c.ws.multigrid.levels[l].col.size());
  state.counters["coarse_nnz"] = coarse / static_cast<double>(std::max<std::size_t>(1, c.ws.compact.col.size()));
  if (c.ws.multigrid.depth > 1) state.counters["level1_nnz_row"] = static_cast<double>(c.ws.multigrid.levels[1].col.size()) / static_cast<double>(c.ws.multigrid.levels[1].rows());
}

void BM_Jacobi(benchmark::State& state) {
  Case c;
  prepare(c, state);
  gf::ColumnD p(c.sim->nodes().size());
  gf::PpeResult r;
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
    gf::ppe_compact(*c.nb, c.ws.problem, c.ws.compact);
    r = gf::ppe_solve_parallel(c.ws.compact, c.ws.problem, c.lp.solver, p);
  }
  label(state, c, r);
}

void BM_Multigrid(benchmark::State& state) {
  Case c;
  prepare(c, state);
  set_multigrid(c, state);
  gf::ColumnD p(c.sim->nodes().size());
  gf::PpeResult r;
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
    gf::ppe_compact(*c.nb, c.ws.problem, c.ws.compact);
    r = gf::ppe_solve_multigrid(c.ws.compact, c.ws.problem, c.sim->nodes(), c.lp, c.ws.multigrid, p);
  }
  label(state, c, r);
}

void BM_Setup(benchmark::State& state) {
  Case c;
  prepare(c, state);
  set_multigrid(c, state);
  gf::ColumnD p(c.sim->nodes().size());
  gf::ppe_compact(*c.nb, c.ws.problem, c.ws.compact);
  gf::ppe_load(c.ws.compact, c.ws.problem, p);
  const double side = c.lp.solver.multigrid.aggregate * c.lp.k.l0;
  for (auto _ : state)
    gf::multigrid_setup(c.ws.compact, c.ws.problem, c.sim->nodes(), side, c.lp.solver.multigrid, c.ws.multigrid);
  state.counters["levels"] = static_cast<double>(c.ws.multigrid.depth);
}

constexpr std::pair<int, int> kTanks[] = {{2, 316}, {3, 22}, {3, 46}};

void tanks(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side"});
  for (auto [d, s] : kTanks) b->Args({d, s});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

// The default settings (sweeps 1, V, scale 1, cubes of 2 l0) and the variants measured against them.
void variants(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side", "sweeps", "cycle", "scale10", "agg10"});
  for (auto [d, s] : kTanks)
    for (auto v : {std::array{1, 1, 10, 20}, {2, 1, 10, 20}, {1, 2, 10, 20}, {1, 1, 15, 20}, {1, 2, 15, 20}, {1, 1, 10, 30}})
      b->Args({d, s, v[0], v[1], v[2], v[3]});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Jacobi)->Apply(tanks);
BENCHMARK(BM_Multigrid)->Apply(variants);
BENCHMARK(BM_Setup)->Apply(variants);

}  // namespace

BENCHMARK_MAIN();
