// Broadphase throughput on the standard benchmark state (scenes/drum_seed000_settled.toml, 47,108
// grains of the settled seed-000 drum), at 1 and 2 TBB threads:
//   BM_CellGridBuild     the uniform grid alone (bounding box, cell of each row, counting sort);
//   BM_NeighborRebuild   one full rebuild_neighbors: grid, re-sort of every column in cell order,
//                        candidate pairs within r_i + r_j + skin, history carried over, incidence;
//   BM_NeedsRebuild      the half-skin displacement check the broadphase runs every step.
// items_per_second counts rows; the rebuild also reports the pairs found and pairs/s.
//
// The state is primed and stepped a few times before any timing, so rows are already in cell order
// and the contact history is real, as at a rebuild in a running simulation. Rebuilding on the same
// positions finds the same rows order (identity permutation, still copied column by column) and
// the same pairs every iteration, so the work does not change across iterations.
//
// Run:  ./build/bench/broadphase_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <exception>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "systems/broadphase/broadphase.hpp"
#include "bench/settled_drum.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace {

// Cell edge the broadphase uses: the largest interaction range plus the skin.
double cell_edge(const gf::Grains& g, double skin) {
  double rmax = 0.0;
  for (std::size_t i = 0; i < g.n; ++i) rmax = std::max(rmax, g.radius.r[i]);
  return 2.0 * rmax + skin;
}

void BM_CellGridBuild(benchmark::State& state) {
  // A benchmark program owns its process, so it may set the thread count here (not in a library).
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  const gf::Grains& g = sim->grains();
  const double edge = cell_edge(g, sim->world().resources.get<gf::BroadphaseState>().skin);
  gf::CellGrid grid;
  grid.build(g.pos.x.span(), g.pos.y.span(), g.pos.z.span(), edge);  // sizes the buffers, untimed
  for (auto _ : state) {
    grid.build(g.pos.x.span(), g.pos.y.span(), g.pos.z.span(), edge);
    benchmark::DoNotOptimize(grid.order.data());
    benchmark::ClobberMemory();
  }
  const auto rows = static_cast<std::int64_t>(g.n);
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["cells"] = static_cast<double>(grid.cells());
  state.SetLabel("items=rows");
}

void BM_NeighborRebuild(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  auto& bp = w.resources.get<gf::BroadphaseState>();
  auto& list = w.resources.get<gf::NeighborList>();
  auto& history = w.resources.get<gf::PairHistory>();
  gf::rebuild_neighbors(g, bp, list, history);  // untimed: settles buffer sizes at this thread count
  for (auto _ : state) {
    gf::rebuild_neighbors(g, bp, list, history);
    benchmark::ClobberMemory();
  }
  const auto rows = static_cast<std::int64_t>(g.n);
  const auto pairs = static_cast<std::int64_t>(list.pairs());
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["pairs/s"] =
      benchmark::Counter(static_cast<double>(state.iterations() * pairs), benchmark::Counter::kIsRate);
  state.SetLabel("items=rows");
}

void BM_NeedsRebuild(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  const gf::Grains& g = sim->grains();
  const auto& bp = sim->world().resources.get<gf::BroadphaseState>();
  bool moved = false;
  for (auto _ : state) {
    moved = gf::needs_rebuild(g, bp);
    benchmark::DoNotOptimize(moved);
  }
  const auto rows = static_cast<std::int64_t>(g.n);
  state.SetItemsProcessed(state.iterations() * rows);
  state.counters["rows"] = static_cast<double>(rows);
  state.SetLabel(moved ? "items=rows (rebuild due)" : "items=rows");
}

// Real time: TBB workers' CPU time is not the main thread's.
BENCHMARK(BM_CellGridBuild)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_NeighborRebuild)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NeedsRebuild)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
