#include "systems/mps/liquid_simulation.hpp"

#include "systems/mps/liquid_step.hpp"
#include "systems/mps/mixing_length.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/ppe.hpp"

namespace gf {

void build_liquid_world(const LiquidScene& scene, World& w) {
  w.clock = Clock{0.0, scene.dt, 0};
  FluidNodes& f = w.tables.add<FluidNodes>();
  generate_nodes(scene.geometry, scene.blocks, scene.params.k.l0, f);
  if (f.count(kFluid) == 0)
    throw SceneError(scene.file.string() + ":" + std::to_string(scene.fluid_line) + ": the [[fluid]] blocks hold no lattice node (each is thinner than "
                     "the spacing l0 = " + short_number(scene.params.k.l0) + " m somewhere, or lies outside the "
                     "geometry). Fix: give each block at least one spacing along every axis, inside the geometry");
  w.resources.emplace<LiquidParams>(scene.params);
  w.resources.emplace<NeighborPairs>();
  w.resources.emplace<PpeWorkspace>();
  w.resources.emplace<LiquidDiagnostics>();
  if (scene.params.mixing_length.on) w.resources.emplace<EddyViscosity>();
  w.resources.emplace<StabilityLimits>(scene.limits());
  if (scene.drive) w.resources.emplace<FlowDrive>(*scene.drive);
}

LiquidSimulation::LiquidSimulation(LiquidScene scene)
    : scene_(std::move(scene)), world_(std::make_unique<World>()), step_(std::make_unique<Schedule>()) {
  World& w = *world_;
  build_liquid_world(scene_, w);
  schedule_liquid_step(*step_, scene_.drive.has_value());
  step_->build(w);
}

LiquidSimulation LiquidSimulation::from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return LiquidSimulation(load_liquid_scene(SceneDoc::load(file, overrides)));
}

LiquidSimulation LiquidSimulation::from_text(std::string_view toml, const std::vector<std::string>& overrides) {
  return LiquidSimulation(load_liquid_scene(SceneDoc::parse(toml, "scene.toml", overrides)));
}

FluidNodes& LiquidSimulation::nodes() { return world_->tables.get<FluidNodes>(); }
LiquidParams& LiquidSimulation::params() { return world_->resources.get<LiquidParams>(); }
const LiquidDiagnostics& LiquidSimulation::diagnostics() { return world_->resources.get<LiquidDiagnostics>(); }

void LiquidSimulation::step_once() {
  step_->run_step(next_step(world_->clock));
  advance_clock(world_->clock);
}

void LiquidSimulation::advance(std::int64_t n) {
  for (std::int64_t k = 0; k < n; ++k) step_once();
}

}  // namespace gf
