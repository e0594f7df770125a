// End-to-end throughput: whole DEM steps (DemSimulation::advance: integrate, broadphase with its
// rebuilds when due, pair and wall contacts, integrate) on a scene, reported as particle-steps/s
// (steps x owned grains per wall-clock second) at 1 and 2 TBB threads. The default scene is the
// standard benchmark state, scenes/drum_seed000_settled.toml (47,108 grains of the settled
// seed-000 drum, rotation starting at 0.5 rad/s).
//
// Each iteration advances a fixed number of steps (200 by default). The scene is loaded, primed
// and stepped a few times once, outside the timed loop; every run then continues from where the
// last one stopped. For the default scene that is a few thousand steps in all (about 0.01 rad of
// drum rotation), so every run sees the same near-rest state; note that the neighbour list is then
// rebuilt rarely, less often than in a drum in steady rotation. `rebuilds/step` reports how often
// it was rebuilt in the timed steps, since that is part of the cost. Time is wall clock (threads).
//
// Run:
//   ./build/bench/end_to_end_bench --benchmark_repetitions=3 --benchmark_report_aggregates_only=true
// Options (before or among the Google Benchmark flags):
//   --scene=PATH     another scene file (also: environment variable GRAINFLOW_BENCH_SCENE); a
//                    relative path is taken from the current directory
//   --steps=N        steps per iteration (also: GRAINFLOW_BENCH_STEPS), default 200
//   --threads=1,2,4  thread counts to measure, default 1,2
//   --set=key=value  scene override, as `grainflow run --set` (repeatable)
//   --settle         run the scene's settling stage first (untimed), for scenes that pour a fill
// e.g. ./build/bench/end_to_end_bench --scene=scenes/drum_quick.toml --set=run.dt=5e-6 --threads=1,2,4
// Without --benchmark_repetitions the program repeats each measurement 3 times.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "systems/broadphase/broadphase.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace {

constexpr const char* kDefaultScene = GRAINFLOW_SOURCE_DIR "/scenes/drum_seed000_settled.toml";
constexpr std::int64_t kDefaultSteps = 200;
constexpr std::int64_t kWarmSteps = 20;
constexpr int kDefaultRepetitions = 3;

struct Options {
  std::filesystem::path scene = kDefaultScene;
  std::int64_t steps = kDefaultSteps;
  std::vector<std::int64_t> threads{1, 2};
  std::vector<std::string> overrides;
  bool settle = false;
  bool repetitions_given = false;
};

// The scene, loaded on first use and kept for every run of the program.
class SceneUnderTest {
 public:
  explicit SceneUnderTest(const Options& opt) : opt_(opt) {}

  gf::DemSimulation& get() {
    if (!sim_) {
      auto sim = std::make_unique<gf::DemSimulation>(gf::DemSimulation::from_file(opt_.scene, opt_.overrides));
      if (opt_.settle)
        sim->settle();  // primes first
      else
        sim->prime();
      sim->advance(kWarmSteps);
      sim_ = std::move(sim);
    }
    return *sim_;
  }

 private:
  const Options& opt_;
  std::unique_ptr<gf::DemSimulation> sim_;
};

void run_end_to_end(benchmark::State& state, SceneUnderTest* scene, std::int64_t steps) {
  // A benchmark program owns its process, so it may set the thread count here (not in a library).
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = nullptr;
  try {
    sim = &scene->get();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  sim->advance(2);  // untimed: wakes the workers of this thread count
  const auto& bp = sim->world().resources.get<gf::BroadphaseState>();
  const std::int64_t rebuilds0 = bp.rebuilds;
  for (auto _ : state) {
    sim->advance(steps);
  }
  const auto grains = static_cast<double>(sim->grains().n_owned);
  const auto total_steps = static_cast<double>(state.iterations() * steps);
  state.counters["grains"] = grains;
  state.counters["steps/s"] = benchmark::Counter(total_steps, benchmark::Counter::kIsRate);
  state.counters["particle_steps/s"] = benchmark::Counter(total_steps * grains, benchmark::Counter::kIsRate);
  state.counters["rebuilds/step"] = static_cast<double>(bp.rebuilds - rebuilds0) / total_steps;
}

bool take_value(std::string_view arg, std::string_view flag, std::string& value) {
  if (arg.size() <= flag.size() || arg.substr(0, flag.size()) != flag || arg[flag.size()] != '=') return false;
  value = std::string(arg.substr(flag.size() + 1));
  return true;
}

std::int64_t parse_count(const std::string& text, const char* what) {
  char* end = nullptr;
  const long long v = std::strtoll(text.c_str(), &end, 10);
  if (end == text.c_str() || *end != '\0' || v < 1) {
    std::fprintf(stderr, "end_to_end_bench: %s must be a positive integer, got '%s'\n", what, text.c_str());
    std::exit(2);
  }
  return v;
}

// Takes this program's own options out of argv and leaves Google Benchmark's flags in place.
Options parse_options(int& argc, char** argv) {
  Options opt;
  if (const char* env = std::getenv("GRAINFLOW_BENCH_SCENE"); env && *env) opt.scene = env;
  if (const char* env = std::getenv("GRAINFLOW_BENCH_STEPS"); env && *env)
    opt.steps = parse_count(env, "GRAINFLOW_BENCH_STEPS");
  int kept = 1;
  for (int a = 1; a < argc; ++a) {
    const std::string_view arg = argv[a];
    std::string value;
    if (take_value(arg, "--scene", value)) {
      opt.scene = value;
    } else if (take_value(arg, "--steps", value)) {
      opt.steps = parse_count(value, "--steps");
    } else if (take_value(arg, "--set", value)) {
      opt.overrides.push_back(value);
    } else if (arg == "--settle") {
      opt.settle = true;
    } else if (take_value(arg, "--threads", value)) {
      opt.threads.clear();
      std::size_t from = 0;
      for (;;) {
        const std::size_t comma = value.find(',', from);
        opt.threads.push_back(parse_count(value.substr(from, comma - from), "each of --threads"));
        if (comma == std::string::npos) break;
        from = comma + 1;
      }
    } else {
      if (arg.starts_with("--benchmark_repetitions")) opt.repetitions_given = true;
      argv[kept++] = argv[a];
    }
  }
  argc = kept;
  return opt;
}

}  // namespace

int main(int argc, char** argv) {
  static Options opt = parse_options(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;

  static SceneUnderTest scene(opt);
  const std::string name = "end_to_end/" + opt.scene.stem().string();
  auto* b = benchmark::RegisterBenchmark(name.c_str(), run_end_to_end, &scene, opt.steps);
  b->ArgName("threads")->UseRealTime()->Unit(benchmark::kSecond);
  for (const std::int64_t t : opt.threads) b->Arg(t);
  if (!opt.repetitions_given) b->Repetitions(kDefaultRepetitions);

  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
