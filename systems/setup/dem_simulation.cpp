#include "systems/setup/dem_simulation.hpp"

#include <algorithm>
#include <type_traits>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/setup/dem_body_checkpoint.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

DemSimulation::DemSimulation(DemScene scene)
    : scene_(std::move(scene)), world_(std::make_unique<World>()), step_(std::make_unique<Schedule>()) {
  build_dem_world(scene_, *world_);
  schedule_dem_step(*step_, scene_);
  step_->build(*world_);
}

DemSimulation DemSimulation::from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return DemSimulation(load_dem_scene(SceneDoc::load(file, overrides)));
}

DemSimulation DemSimulation::from_text(std::string_view toml, const std::vector<std::string>& overrides) {
  return DemSimulation(load_dem_scene(SceneDoc::parse(toml, "scene.toml", overrides)));
}

void DemSimulation::prime() {
  StepContext now = next_step(world_->clock);
  now.prime = true;
  try {
    step_->run_step(now);
  } catch (const StabilityError& e) {
    // Nothing has moved yet: the fills placed the grains past the overlap limit, a scene error.
    const int line = !scene_.fills.empty() ? scene_.fills.front().line : scene_.bodies ? scene_.bodies->line : 0;
    throw SceneError(scene_.file.string() + ":" + std::to_string(line) + ": the fills' initial state: " + e.what());
  }
  primed_ = true;
  // The law advanced every spring by v_t dt while evaluating; no time has passed, and the springs
  // of a new state start from zero, so that increment is undone.
  world_->resources.get<PairHistory>().clear();
  for_each_column(world_->grains.extras.get<WallHistory>(), [](auto& c) {
    std::fill(c.begin(), c.end(), typename std::decay_t<decltype(c)>::value_type{});
  });
  if (BodyContactState* b = world_->resources.find<BodyContactState>()) {
    b->history.clear();
    std::fill(b->walls.value.begin(), b->walls.value.end(), 0.0);
  }
}

StageReport DemSimulation::settle(double progress_seconds) {
  if (!primed_) prime();
  StageReport rep;
  if (scene_.settle_steps() <= 0) return rep;
  Walls& walls = world_->resources.get<Walls>();
  walls.rotation_enabled = false;
  StageOptions so;
  so.label = "settle";
  so.steps = scene_.settle_steps();
  if (scene_.bodies)  // progress in body-steps
    so.rows = [w = world_.get()](const World&) {
      const Bodies& b = w->tables.get<Bodies>();
      double n = 0;
      for (std::size_t i = 0; i < b.n; ++i) n += b.moving(i);
      return n;
    };
  so.progress_seconds = progress_seconds;
  rep = run_stage(*world_, *step_, so);
  walls.rotation_enabled = true;
  world_->clock.t = 0.0;
  world_->clock.step = 0;
  return rep;
}

void DemSimulation::resume(const CheckpointReader& in) {
  if (scene_.bodies)
    restore_body_state(in, *world_, scene_);
  else
    restore_dem_state(in, *world_, scene_);
  primed_ = true;
}

void DemSimulation::advance(std::int64_t n) {
  if (!primed_) prime();
  StageOptions so;
  so.steps = n;
  so.progress_seconds = 0.0;
  run_stage(*world_, *step_, so);
}

}  // namespace gf
