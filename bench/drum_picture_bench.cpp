// Cost of one drum picture of the standard settled drum (47,108 grains, 800 px): rendering alone,
// and rendering plus PNG encoding and the atomic write.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "bench/settled_drum.hpp"
#include "systems/output/drum_picture.hpp"

namespace {

struct Setup {
  gf::PictureGrains grains;
  gf::DrumSection section;
  gf::PictureOptions options;
};

bool setup(benchmark::State& state, Setup& s) {
  const auto drum = gf::bench::settled_drum_with_section(state);
  if (!drum) return false;
  const gf::Grains& g = drum->sim->world().grains;
  const std::size_t n = g.n_owned;
  s.grains = {{g.pos.x.data(), n},    {g.pos.y.data(), n},        {g.pos.z.data(), n},
              {g.radius.r.data(), n}, {g.species.type.data(), n}, {}};
  s.section = drum->section;
  std::vector<double> d;
  for (const auto& sp : drum->sim->scene().species) d.push_back(sp.mean_diameter());
  s.options.palette = gf::species_palette(d);
  s.options.size = static_cast<int>(state.range(0));
  return true;
}

void BM_RenderPicture(benchmark::State& state) {
  Setup s;
  if (!setup(state, s)) return;
  for (auto _ : state) benchmark::DoNotOptimize(gf::render_drum_picture(s.grains, s.section, s.options));
}
BENCHMARK(BM_RenderPicture)->Arg(800)->Unit(benchmark::kMillisecond);

void BM_RenderAndWritePicture(benchmark::State& state) {
  Setup s;
  if (!setup(state, s)) return;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("grainflow_picture_bench_" + std::to_string(::getpid()) + ".png");
  for (auto _ : state) gf::write_png(file, gf::render_drum_picture(s.grains, s.section, s.options));
  std::filesystem::remove(file);
}
BENCHMARK(BM_RenderAndWritePicture)->Arg(800)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
