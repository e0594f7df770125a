// End-to-end MPS step throughput on still tanks (bench/mps_tank.hpp): steps/s and fluid particle-steps/s
// (items_per_second) for 2D and 3D tanks of ~1e4 and ~1e5 fluid nodes, with each PPE solver; beside them the
// pressure solve's share of the step (ppe_share: the pressure_solve system's time, divergence, source,
// assembly and solve, over all systems' time) and the CG iterations per step (ppe_iterations).
//   args: dim, side (nodes per edge), solver (0 parallel CG, 1 Eigen CG Jacobi)
// BM_MpsStepMultigrid: the parallel CG with the multigrid preconditioner, its hierarchy rebuilt every step
// (reuse:1) or kept for 20 steps (reuse:20; solver.multigrid_reuse).
//
// Run:  ./build/bench/mps_step_bench --benchmark_min_time=2
#include <benchmark/benchmark.h>

#include <string>

#include "bench/mps_tank.hpp"

namespace {

void measure_steps(benchmark::State& state, gf::LiquidSimulation* sim) {
  sim->step().reset_timings();
  const double iterations_before = sim->diagnostics().ppe_iterations_total;
  for (auto _ : state) sim->step_once();
  const auto fluid = static_cast<std::int64_t>(sim->nodes().count(gf::kFluid));
  double all = 0, ppe = 0;
  for (const gf::SystemTiming& t : sim->step().timings()) {
    all += t.seconds;
    if (t.name == "pressure_solve") ppe += t.seconds;
  }
  const auto steps = static_cast<double>(state.iterations());
  state.SetItemsProcessed(state.iterations() * fluid);
  state.counters["fluid"] = static_cast<double>(fluid);
  state.counters["nodes"] = static_cast<double>(sim->nodes().size());
  state.counters["steps_per_s"] = benchmark::Counter(steps, benchmark::Counter::kIsRate);
  state.counters["ppe_share"] = all > 0 ? ppe / all : 0.0;
  state.counters["ppe_iterations"] = (sim->diagnostics().ppe_iterations_total - iterations_before) / steps;
  state.SetLabel("items=fluid particle-steps");
}

void BM_MpsStep(benchmark::State& state) {
  const int dim = static_cast<int>(state.range(0)), side = static_cast<int>(state.range(1));
  auto sim = gf::bench::liquid_tank(dim, side, state.range(2) ? R"(kind = "eigen_cg")" : R"(kind = "parallel_cg")", 2);
  measure_steps(state, sim.get());
}

void BM_MpsStepMultigrid(benchmark::State& state) {
  const int dim = static_cast<int>(state.range(0)), side = static_cast<int>(state.range(1));
  const std::string keys = R"(preconditioner = "multigrid", multigrid_reuse = )" + std::to_string(state.range(2));
  auto sim = gf::bench::liquid_tank(dim, side, keys, 2);
  measure_steps(state, sim.get());
}

void sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side", "eigen"});
  for (auto [d, s] : {std::pair{2, 100}, {2, 316}, {3, 22}, {3, 46}})
    for (int e : {0, 1}) b->Args({d, s, e});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_MpsStep)->Apply(sizes);

void multigrid_sizes(benchmark::internal::Benchmark* b) {
  b->ArgNames({"dim", "side", "reuse"});
  for (auto [d, s] : {std::pair{2, 316}, {3, 22}, {3, 46}})
    for (int r : {1, 20}) b->Args({d, s, r});
  b->UseRealTime()->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_MpsStepMultigrid)->Apply(multigrid_sizes);

}  // namespace

BENCHMARK_MAIN();
