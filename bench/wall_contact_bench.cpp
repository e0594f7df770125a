// Particle-wall contact throughput: compute_wall_forces (every owned row against every wall of the
// drum: the rotating cylinder and its two end plates) on the standard benchmark state
// (scenes/drum_seed000_settled.toml, 47,108 grains), at 1 and 2 TBB threads. items_per_second
// counts rows; the `touching` counter is the number of rows in contact with some wall.
//
// The drum is primed and stepped a few times first, so the wall springs are those of a running
// simulation. Iterations re-evaluate the same positions at the same wall angle: the contacts and
// so the work are fixed, while the wall springs keep integrating v_t dt (clipped at the caps), so
// the history evolves a little. That changes values, not the amount of work.
//
// Run:  ./build/bench/wall_contact_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <cstddef>
#include <cstdint>
#include <exception>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "bench/settled_drum.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "systems/contact/laws.hpp"
#include "systems/walls/wall_contact.hpp"

namespace {

// Rows touching at least one wall at the walls' current placement.
std::int64_t count_touching(const gf::Grains& g, const gf::Walls& walls) {
  std::int64_t n = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const gf::Vec3d p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
    for (const gf::Wall& wall : walls.list) {
      gf::Vec3d towards;
      if (gf::wall_gap(wall, p, towards) < g.radius.r[i]) {
        ++n;
        break;
      }
    }
  }
  return n;
}

template <auto Driver>
void BM_WallForces(benchmark::State& state) {
  // A benchmark program owns its process, so it may set the thread count here (not in a library).
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  auto& walls = w.resources.get<gf::Walls>();
  auto& history = g.extras.get<gf::WallHistory>();
  const auto& table = w.resources.get<gf::ContactTable>();
  const double dt = w.clock.dt;
  const double t = w.clock.t;  // positions of the last completed step refer to this time
  for (auto _ : state) {
    Driver(g, walls, history, table, dt, t, w.resources.get<gf::OverlapLimit>().ratio);
    benchmark::ClobberMemory();
  }
  const auto rows = static_cast<std::int64_t>(g.n_owned);
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["walls"] = static_cast<double>(walls.list.size());
  state.counters["touching"] = static_cast<double>(count_touching(g, walls));
  state.SetLabel("items=rows");
}

// Real time: TBB workers' CPU time is not the main thread's.
BENCHMARK_TEMPLATE(BM_WallForces, gf::compute_wall_forces<gf::LinearSpringDashpot>)->Name("BM_WallForces/simd")->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(BM_WallForces, gf::compute_wall_forces_scalar<gf::LinearSpringDashpot>)->Name("BM_WallForces/scalar")->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
