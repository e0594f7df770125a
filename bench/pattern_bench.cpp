// Cost of the drum pattern classifier (one call per series row) on the standard settled drum,
// 47,108 grains: rows/s of one classify_pattern call.
#include <benchmark/benchmark.h>

#include "bench/settled_drum.hpp"
#include "systems/analysis/pattern.hpp"

namespace {

void BM_ClassifyPattern(benchmark::State& state) {
  const auto drum = gf::bench::settled_drum_with_section(state);
  if (!drum) return;
  const gf::Grains& g = drum->sim->world().grains;
  const std::size_t n = g.n_owned;
  const gf::PatternGrains pg{{g.pos.x.data(), n},
                             {g.pos.y.data(), n},
                             {g.pos.z.data(), n},
                             {g.radius.r.data(), n},
                             {g.species.type.data(), n}};
  gf::PatternSettings settings;
  settings.large_type = drum->sim->scene().segregation_type;
  for (auto _ : state) benchmark::DoNotOptimize(gf::classify_pattern(pg, drum->section, settings));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}
BENCHMARK(BM_ClassifyPattern)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
