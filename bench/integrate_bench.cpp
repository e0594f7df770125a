// Velocity-Verlet integration throughput on the standard benchmark state
// (scenes/drum_seed000_settled.toml, 47,108 grains), at 1 and 2 TBB threads:
//   BM_KickDrift   kick (v, w += dt/2 a, alpha) and drift (x += dt v) in one pass: integrate_positions' work;
//   BM_Kick        kick alone: integrate_velocities' work.
// items_per_second counts rows.
//
// The drum is primed and stepped a few times first, so forces and torques are real. Iterations
// alternate the sign of the step (+dt, -dt, ...): velocities then return to their start after every
// two iterations and positions move by only dt^2/2 a per two iterations, so the state stays the
// drum's. The work is the same either way (straight-line arithmetic over contiguous columns).
//
// Run:  ./build/bench/integrate_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <cstddef>
#include <cstdint>
#include <exception>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "systems/integrate/integrate.hpp"
#include "bench/settled_drum.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace {

void BM_KickDrift(benchmark::State& state) {
  // A benchmark program owns its process, so it may set the thread count here (not in a library).
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  const auto& gravity = w.resources.get<gf::Gravity>();
  const gf::ForceTerms terms = gf::dem_force_terms(sim->scene());
  double dt = w.clock.dt;
  for (auto _ : state) {
    gf::kick_drift(g, terms, gravity, 0.5 * dt, dt);
    benchmark::ClobberMemory();
    dt = -dt;
  }
  const auto rows = static_cast<std::int64_t>(g.n_owned);
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.SetLabel("items=rows");
}

void BM_Kick(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  const auto& gravity = w.resources.get<gf::Gravity>();
  const gf::ForceTerms terms = gf::dem_force_terms(sim->scene());
  double h = 0.5 * w.clock.dt;
  for (auto _ : state) {
    gf::kick(g, terms, gravity, h);
    benchmark::ClobberMemory();
    h = -h;
  }
  const auto rows = static_cast<std::int64_t>(g.n_owned);
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.SetLabel("items=rows");
}

// Real time: TBB workers' CPU time is not the main thread's.
BENCHMARK(BM_KickDrift)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Kick)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
