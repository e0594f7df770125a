#include "systems/setup/coupled_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "engine/run_loop.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/coupling/coupled_step.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/mps/liquid_fraction.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/liquid_step.hpp"
#include "systems/mps/mps_coupled_liquid.hpp"
#include "systems/setup/coupled_checkpoint.hpp"
#include "systems/walls/contact_systems.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

namespace {

// The DEM step of the scene with the liquid's force as one more force term (grains of spheres, no feeds).
std::unique_ptr<Schedule> coupled_dem_step(const DemScene& scene, const CouplingSpec& coupling) {
  ForceTerms terms = dem_force_terms(scene);
  terms.list.push_back(liquid_force_term(coupling));
  auto step = std::make_unique<Schedule>();
  step->emplace<IntegratePositions>(terms);
  step->emplace<Broadphase>();
  add_contact_systems(*step, {scene.law, !scene.walls.empty(), !scene.mesh_walls.list.empty()});
  add_liquid_force(*step);
  step->emplace<IntegrateVelocities>(terms);
  return step;
}

// What the coupling keeps of the MPS liquid: a node stands for l0^3 of clear liquid.
LiquidFacts liquid_facts(const LiquidScene& liquid) {
  const LiquidParams& p = liquid.params;
  return {{p.rho, p.rho * p.nu}, std::pow(p.k.l0, 3), p.periodic.axis, p.periodic.lo, p.periodic.hi};
}

}  // namespace

CoupledSimulation::CoupledSimulation(CoupledScene scene)
    : scene_(std::move(scene)), world_(std::make_unique<World>()), step_(std::make_unique<Schedule>()) {
  World& w = *world_;
  build_dem_world(scene_.dem, w);
  build_liquid_world(scene_.liquid, w);  // the clock: the liquid's step
  attach_coupling(scene_.coupling, liquid_facts(scene_.liquid), w);
  if (scene_.coupling.averaged) w.resources.emplace<LiquidFraction>();  // the liquid's target: eps n0
  auto inner = scene_.coupling.fixed_grains ? fixed_grains_step() : coupled_dem_step(scene_.dem, scene_.coupling);
  dem_ = &schedule_coupled_step<MpsCoupledLiquid>(*step_, std::move(inner), scene_.coupling.substeps);
  schedule_liquid_step(*step_, scene_.liquid.drive.has_value());
  step_->build(w);
}

CoupledSimulation CoupledSimulation::from_file(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return CoupledSimulation(load_coupled_scene(SceneDoc::load(file, overrides)));
}

CoupledSimulation CoupledSimulation::from_text(std::string_view toml, const std::vector<std::string>& overrides) {
  return CoupledSimulation(load_coupled_scene(SceneDoc::parse(toml, "scene.toml", overrides)));
}

void CoupledSimulation::prime() {
  World& w = *world_;
  const int line = scene_.dem.fills.empty() ? 0 : scene_.dem.fills.front().line;
  try {
    prepare_coupling<MpsCoupledLiquid>(w);
  } catch (const std::runtime_error& e) {  // a grain placed where no liquid node reaches it
    throw SceneError(scene_.file.string() + ":" + std::to_string(line) + ": the fills' initial state: " + e.what());
  }
  StepContext now = next_step(w.clock);
  now.dt /= scene_.coupling.substeps;
  now.substeps = scene_.coupling.substeps;
  now.prime = true;
  try {
    dem_->inner().run_step(now);
  } catch (const StabilityError& e) {
    throw SceneError(scene_.file.string() + ":" + std::to_string(line) + ": the fills' initial state: " + e.what());
  } catch (const std::invalid_argument& e) {  // the drag of a state packed past any void fraction, say
    throw SceneError(scene_.file.string() + ":" + std::to_string(line) + ": the fills' initial state: " + e.what() +
                     ". Fix: check the state file's positions and diameters: grains packed past any liquid fraction, "
                     "or placed where no liquid is, leave none in (0, 1]");
  }
  primed_ = true;
  // Priming advanced the contact springs by v_t dt; a new state's springs start from zero.
  w.resources.get<PairHistory>().clear();
  for_each_column(w.grains.extras.get<WallHistory>(), [](auto& c) {
    std::fill(c.begin(), c.end(), typename std::decay_t<decltype(c)>::value_type{});
  });
}

void CoupledSimulation::step_once() {
  if (!primed_) prime();
  step_->run_step(next_step(world_->clock));
  advance_clock(world_->clock);
}

void CoupledSimulation::resume(const CheckpointReader& in) {
  restore_coupled_state(in, *world_, scene_);
  primed_ = true;  // the forces, springs and the liquid's force on the grains are the checkpoint's
}

void CoupledSimulation::advance(std::int64_t n) {
  for (std::int64_t k = 0; k < n; ++k) step_once();
}

}  // namespace gf
