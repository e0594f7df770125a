// Mesh-wall contact throughput: compute_mesh_wall_forces (every owned row against every mesh) in the
// seed-004 mixer, design 1 (scenes/mixer_seed004_design1.toml: a 48-facet housing, five rings and
// twelve blade plates, 18 meshes turning together), holding the bed of a steady run
// (scenes/data/mixer_design1_steady.csv), with the representative-volume law; 1 and 2 TBB threads.
// items_per_second counts rows; `touching` is the number of rows with a mesh contact.
//
// The mixer is primed and stepped a few times first, so the mesh springs are those of a running
// simulation. Iterations re-evaluate the same positions at the same angle: the work is fixed.
//
// Run:  ./build/bench/mesh_wall_contact_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <cstddef>
#include <cstdint>
#include <exception>
#include <fstream>
#include <sstream>
#include <string>

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include "systems/analysis/metrics.hpp"
#include "systems/contact/laws.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "systems/walls/mesh_wall_contact.hpp"

namespace {

constexpr const char* kScene = GRAINFLOW_SOURCE_DIR "/scenes/mixer_seed004_design1.toml";
constexpr const char* kState = GRAINFLOW_SOURCE_DIR "/scenes/data/mixer_design1_steady.csv";

// The mixer scene with the steady bed as its fill (the feed and outlet stay idle: no step runs here
// past the warm-up, and the warm-up starts at t = 0, before the first feed event adds anything).
gf::DemSimulation& mixer() {
  static gf::DemSimulation sim = [] {
    std::ifstream in(kScene);
    std::stringstream text;
    text << in.rdbuf() << "\n[[fill]]\nkind = \"file\"\npath = \"" << kState
         << "\"\ntypes = { 1 = \"carrier\", 2 = \"key\" }\n";
    gf::DemSimulation s = gf::DemSimulation::from_text(text.str());
    s.prime();
    s.advance(20);
    return s;
  }();
  return sim;
}

void BM_MeshWallForces(benchmark::State& state) {
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(state.range(0)));
  gf::DemSimulation* sim = nullptr;
  try {
    sim = &mixer();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  gf::World& w = sim->world();
  gf::Grains& g = w.grains;
  const auto& walls = w.resources.get<gf::MeshWalls>();
  const auto& table = w.resources.get<gf::ContactTable>();
  const double dt = w.clock.dt, t = w.clock.t;
  for (auto _ : state) {
    gf::compute_mesh_wall_forces<gf::RepresentativeVolume>(g, walls, true, table, dt, t, 1.0, true);
    benchmark::ClobberMemory();
  }
  gf::ContactStats touching;
  gf::add_mesh_contacts(touching, g, walls, t, true);
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(g.n_owned));
  state.counters["rows"] = static_cast<double>(g.n_owned);
  state.counters["meshes"] = static_cast<double>(walls.list.size());
  state.counters["contacts"] = static_cast<double>(touching.wall_contacts);
  state.SetLabel("items=rows");
}

BENCHMARK(BM_MeshWallForces)->ArgName("threads")->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
