// Cost of the drum pattern classifier (one call per series row) on the standard settled drum,
// 47,108 grains: rows/s of one classify_pattern call.
#include <benchmark/benchmark.h>

#include "bench/settled_drum.hpp"
#include "systems/analysis/pattern.hpp"

namespace {

void BM_ClassifyPattern(benchmark::State& state) {
  gf::DemSimulation* sim = gf::bench::settled_drum_or_skip(state);
  if (!sim) return;
  const auto section = gf::bench::settled_drum_section(state, *sim);
  if (!section) return;
  const gf::Grains& g = sim->world().grains;
  const std::size_t n = g.n_owned;
  const gf::PatternGrains pg{{g.pos.x.data(), n},
                             {g.pos.y.data(), n},
                             {g.pos.z.data(), n},
                             {g.radius.r.data(), n},
                             {g.species.type.data(), n}};
  gf::PatternSettings settings;
  settings.large_type = sim->scene().segregation_type;
  for (auto _ : state) benchmark::DoNotOptimize(gf::classify_pattern(pg, *section, settings));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}
BENCHMARK(BM_ClassifyPattern)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
