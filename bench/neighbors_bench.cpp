// The liquid's neighbour list build (systems/mps/neighbors.hpp) on still tanks of about 1e4 and 1e5 fluid nodes
// (bench/mps_tank.hpp): ms per build and pairs per second, at the liquid's search radius r_e + skin.
//   args: dim, side (nodes per edge)
//
// Run:  ./build/bench/neighbors_bench --benchmark_min_time=1
#include <benchmark/benchmark.h>

#include "bench/mps_tank.hpp"
#include "systems/mps/neighbors.hpp"

namespace {

void BM_BuildNeighbors(benchmark::State& state) {
  gf::LiquidSimulation& sim = gf::bench::shared_liquid_tank(static_cast<int>(state.range(0)),
                                                            static_cast<int>(state.range(1)));
  const gf::LiquidParams& lp = sim.params();
  gf::NeighborPairs nb = sim.world().resources.get<gf::NeighborPairs>();
  for (auto _ : state) {
    gf::build_neighbors(sim.nodes(), lp.k.re + lp.skin, lp.periodic, nb);
    benchmark::DoNotOptimize(nb.j.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(nb.pairs()));
  state.counters["nodes"] = static_cast<double>(sim.nodes().size());
  state.counters["pairs"] = static_cast<double>(nb.pairs());
  state.SetLabel("items=pairs");
}

BENCHMARK(BM_BuildNeighbors)
    ->ArgNames({"dim", "side"})
    ->Args({3, 22})
    ->Args({3, 46})
    ->Args({2, 316})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
