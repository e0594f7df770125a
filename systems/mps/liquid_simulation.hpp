// A liquid scene made runnable: the world (the FluidNodes table and the liquid's resources) and the step schedule. The CLI,
// the tests and the benchmarks all drive liquid scenes through this one type.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "engine/schedule.hpp"
#include "systems/mps/liquid_scene.hpp"

namespace gf {

// The FluidNodes table of the scene's blocks and the liquid's resources, added to `world`; the clock set to
// the liquid's step. A SceneError when the blocks hold no node.
void build_liquid_world(const LiquidScene& scene, World& world);

class LiquidSimulation {
 public:
  explicit LiquidSimulation(LiquidScene scene);
  static LiquidSimulation from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static LiquidSimulation from_text(std::string_view toml, const std::vector<std::string>& overrides = {});

  // One step: the schedule, then the clock. Throws LiquidFailure when a stability detector fires.
  void step_once();
  void advance(std::int64_t n);

  LiquidScene& scene() { return scene_; }
  World& world() { return *world_; }
  FluidNodes& nodes();
  LiquidParams& params();
  const LiquidDiagnostics& diagnostics();
  Schedule& step() { return *step_; }

 private:
  LiquidScene scene_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Schedule> step_;
};

}  // namespace gf
