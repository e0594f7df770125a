// Cost of the free surface (one call per series row of a drum with two species) on the standard
// settled drum, 47,108 grains: rows/s of one free_surface call with the surface speed.
#include <benchmark/benchmark.h>

#include "bench/settled_drum.hpp"
#include "systems/analysis/free_surface.hpp"

namespace {

void BM_FreeSurface(benchmark::State& state) {
  const auto drum = gf::bench::settled_drum_with_section(state);
  if (!drum) return;
  const gf::Grains& g = drum->sim->world().grains;
  const std::size_t n = g.n_owned;
  const gf::SurfaceGrains sg{{g.pos.x.data(), n}, {g.pos.y.data(), n}, {g.pos.z.data(), n}, {g.radius.r.data(), n},
                             {g.vel.x.data(), n}, {g.vel.y.data(), n}, {g.vel.z.data(), n}};
  for (auto _ : state) benchmark::DoNotOptimize(gf::free_surface(sg, drum->section));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
}
BENCHMARK(BM_FreeSurface)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
