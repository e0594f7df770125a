// The standard benchmark state shared by the per-system benchmarks: scenes/drum_seed000_settled.toml
// (47,108 grains), primed and stepped a few times so the neighbour list and the contact springs are
// those of a running simulation. Built once, on first use, outside every timed loop.
#pragma once

#include <cstdint>
#include <exception>
#include <optional>

#include <benchmark/benchmark.h>

#include "systems/analysis/drum_section.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace gf::bench {

inline constexpr const char* kDrumScene = GRAINFLOW_SOURCE_DIR "/scenes/drum_seed000_settled.toml";
inline constexpr std::int64_t kWarmSteps = 20;

inline DemSimulation& settled_drum() {
  static DemSimulation sim = [] {
    DemSimulation s = DemSimulation::from_file(kDrumScene);
    s.prime();
    s.advance(kWarmSteps);
    return s;
  }();
  return sim;
}

// The drum, or nullptr with the benchmark marked as failed (and why) when the scene cannot load.
inline DemSimulation* settled_drum_or_skip(benchmark::State& state) {
  try {
    return &settled_drum();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return nullptr;
  }
}

// The drum's cross-section in the lab frame, or none with the benchmark marked as failed.
inline std::optional<DrumSection> settled_drum_section(benchmark::State& state, DemSimulation& sim) {
  const Walls& walls = sim.world().resources.get<Walls>();
  const Gravity& gr = sim.world().resources.get<Gravity>();
  const auto drum = find_drum(walls);
  if (!drum) {
    state.SkipWithError("the settled drum scene has no drum wall");
    return std::nullopt;
  }
  return drum_section(walls.list[*drum], {gr.x, gr.y, gr.z});
}

// The drum and its cross-section, or none with the benchmark marked as failed: the set-up of the
// benchmarks of the drum analyses.
struct SettledDrum {
  DemSimulation* sim;
  DrumSection section;
};
inline std::optional<SettledDrum> settled_drum_with_section(benchmark::State& state) {
  DemSimulation* sim = settled_drum_or_skip(state);
  if (!sim) return std::nullopt;
  const auto section = settled_drum_section(state, *sim);
  if (!section) return std::nullopt;
  return SettledDrum{sim, *section};
}

}  // namespace gf::bench
