// A DEM scene made runnable: the world, the step schedule, the priming pass and the settling
// stage. The CLI, the tests and the benchmarks all drive scenes through this one type.
#pragma once

#include <cstdint>
#include <memory>

#include "engine/checkpoint_file.hpp"
#include "engine/run_loop.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

class DemSimulation {
 public:
  // Loads and validates the scene, creates the grains of every fill and builds the schedule.
  explicit DemSimulation(DemScene scene);
  static DemSimulation from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static DemSimulation from_text(std::string_view toml, const std::vector<std::string>& overrides = {});

  // Computes the forces of the initial state without moving anything (once, before stepping), so
  // the first half-kick uses a(0); contact springs stay at zero, as a new state starts. Grains that
  // start past the overlap limit are a SceneError at the first [[fill]] (`check` primes too).
  void prime();
  // Runs the scene's settling stage (walls not rotating), then resets the clock to 0.
  StageReport settle(double progress_seconds = 0.0);
  // Advances n steps with no observers; primes first if that has not been done.
  void advance(std::int64_t n);
  // Replaces the state by a checkpoint's (see dem_checkpoint.hpp); the run then continues from it.
  void resume(const CheckpointReader& in);

  DemScene& scene() { return scene_; }
  World& world() { return *world_; }
  Grains& grains() { return world_->grains; }
  Schedule& step() { return *step_; }

 private:
  DemScene scene_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Schedule> step_;
  bool primed_ = false;
};

}  // namespace gf
