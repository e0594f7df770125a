// A coupled scene made runnable: one world holding the liquid's nodes and the grains, one clock (the
// liquid's step), and one schedule, the coupled step of systems/coupling/coupled_step.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/schedule.hpp"
#include "engine/sub_schedule.hpp"
#include "systems/setup/coupled_scene.hpp"

namespace gf {

class CoupledSimulation {
 public:
  explicit CoupledSimulation(CoupledScene scene);
  static CoupledSimulation from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static CoupledSimulation from_text(std::string_view toml, const std::vector<std::string>& overrides = {});

  // The coupling and the grains' forces of the initial state, nothing moved (once, before stepping).
  void prime();
  // One liquid step with its k DEM sub-steps; primes first if that has not been done.
  void step_once();
  void advance(std::int64_t n);
  // Continues from a checkpoint of this scene's run (coupled_checkpoint.hpp) instead of priming.
  void resume(const CheckpointReader& in);

  CoupledScene& scene() { return scene_; }
  World& world() { return *world_; }
  Schedule& step() { return *step_; }
  SubSchedule& dem_substeps() { return *dem_; }

 private:
  CoupledScene scene_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Schedule> step_;
  SubSchedule* dem_ = nullptr;
  bool primed_ = false;
};

}  // namespace gf
