// Pressure Poisson equation of the MPS liquid (systems/mps/ppe.hpp): assembly and solve, separately, for the two
// solvers, on running 2D and 3D tanks (bench/mps_tank.hpp) of about 1e4 and 1e5 fluid nodes.
//   BM_Prepare          source, active set and diagonal
//   BM_AssembleEigen    prepare + Eigen sparse matrix (row-major, compressed)
//   BM_CompactParallel  prepare + the compact copy of the couplings the parallel CG solves on
//   BM_SolveParallel    Jacobi CG over the compact couplings (TBB, deterministic reductions)
//   BM_SolveEigen       Eigen ConjugateGradient, Jacobi (pc = 0) or incomplete-Cholesky (pc = 1) preconditioner
// Every solve starts from p = 0 to tolerance 1e-8; counters: unknowns, iterations.
//
// Run:  ./build/bench/mps_ppe_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
#include <tuple>

#include <benchmark/benchmark.h>

#include "bench/mps_tank.hpp"
#include "systems/mps/ppe.hpp"

namespace {

gf::LiquidSimulation& tank(int dim, int side) { return gf::bench::shared_liquid_tank(dim, side); }

struct Case {
  gf::LiquidSimulation* sim;
  gf::PpeWorkspace ws;
};

void prepare_case(Case& c, int dim, int side) {
  c.sim = &tank(dim, side);
  gf::ppe_prepare(c.sim->nodes(), c.sim->world().resources.get<gf::NeighborPairs>(), c.sim->params(),
                  c.sim->scene().dt, c.ws.problem);
}

void label(benchmark::State& state, const Case& c) {
  state.counters["unknowns"] = static_cast<double>(c.ws.problem.unknowns);
  state.counters["fluid"] = static_cast<double>(c.sim->nodes().count(gf::kFluid));
}

void BM_Prepare(benchmark::State& state) {
  Case c;
  prepare_case(c, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto& nb = c.sim->world().resources.get<gf::NeighborPairs>();
  for (auto _ : state) gf::ppe_prepare(c.sim->nodes(), nb, c.sim->params(), c.sim->scene().dt, c.ws.problem);
  label(state, c);
}

void BM_AssembleEigen(benchmark::State& state) {
  Case c;
  prepare_case(c, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto& nb = c.sim->world().resources.get<gf::NeighborPairs>();
  for (auto _ : state) {
    gf::ppe_prepare(c.sim->nodes(), nb, c.sim->params(), c.sim->scene().dt, c.ws.problem);
    gf::ppe_assemble_eigen(nb, c.ws.problem, c.ws.eigen);
  }
  label(state, c);
  state.counters["nonzeros"] = static_cast<double>(c.ws.eigen.A.nonZeros());
}

void BM_CompactParallel(benchmark::State& state) {
  Case c;
  prepare_case(c, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto& nb = c.sim->world().resources.get<gf::NeighborPairs>();
  for (auto _ : state) {
    gf::ppe_prepare(c.sim->nodes(), nb, c.sim->params(), c.sim->scene().dt, c.ws.problem);
    gf::ppe_compact(nb, c.ws.problem, c.ws.compact);
  }
  label(state, c);
  state.counters["nonzeros"] = static_cast<double>(c.ws.compact.col.size() + c.ws.compact.node_of.size());
}

void BM_SolveParallel(benchmark::State& state) {
  Case c;
  prepare_case(c, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto& nb = c.sim->world().resources.get<gf::NeighborPairs>();
  gf::ppe_compact(nb, c.ws.problem, c.ws.compact);
  gf::ColumnD p(c.sim->nodes().size());
  gf::PpeResult r;
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
    r = gf::ppe_solve_parallel(c.ws.compact, c.ws.problem, c.sim->params().solver, p);
  }
  if (!r.converged) state.SkipWithError("did not converge");
  label(state, c);
  state.counters["iterations"] = r.iterations;
}

void BM_SolveEigen(benchmark::State& state) {
  Case c;
  prepare_case(c, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const auto& nb = c.sim->world().resources.get<gf::NeighborPairs>();
  gf::ppe_assemble_eigen(nb, c.ws.problem, c.ws.eigen);
  gf::PpeSettings s = c.sim->params().solver;
  s.preconditioner = state.range(2) ? gf::Preconditioner::IncompleteCholesky : gf::Preconditioner::Jacobi;
  gf::ColumnD p(c.sim->nodes().size());
  gf::PpeResult r;
  for (auto _ : state) {
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
    r = gf::ppe_solve_eigen(c.ws.eigen, c.ws.problem, s, p);
  }
  if (!r.converged) state.SkipWithError("did not converge");
  label(state, c);
  state.counters["iterations"] = r.iterations;
}

// (dim, side): 2D 100^2 = 1e4 and 316^2 = 1e5 fluid nodes; 3D 22^3 = 1.06e4 and 46^3 = 9.7e4.
void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side"});
  for (auto [d, s] : {std::pair{2, 100}, {2, 316}, {3, 22}, {3, 46}}) b->Args({d, s});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}
void sizes_pc(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side", "pc"});
  for (auto [d, s] : {std::pair{2, 100}, {2, 316}, {3, 22}, {3, 46}})
    for (int pc : {0, 1}) b->Args({d, s, pc});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Prepare)->Apply(sizes);
BENCHMARK(BM_AssembleEigen)->Apply(sizes);
BENCHMARK(BM_CompactParallel)->Apply(sizes);
BENCHMARK(BM_SolveParallel)->Apply(sizes);
BENCHMARK(BM_SolveEigen)->Apply(sizes_pc);

}  // namespace

BENCHMARK_MAIN();
