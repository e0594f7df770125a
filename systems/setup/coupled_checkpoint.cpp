#include "systems/setup/coupled_checkpoint.hpp"

#include <string>

#include "engine/clock_checkpoint.hpp"
#include "engine/scene.hpp"
#include "systems/mps/liquid_checkpoint.hpp"
#include "systems/setup/dem_checkpoint.hpp"

namespace gf {

void save_coupled_state(CheckpointWriter& out, World& world, const CoupledScene& scene) {
  save_clock(out, world.clock);
  out.value("coupling.substeps", static_cast<std::int64_t>(scene.coupling.substeps));
  save_dem_rows(out, world, scene.dem);
  save_liquid_nodes(out, world, scene.liquid);
}

void restore_coupled_state(const CheckpointReader& in, World& world, const CoupledScene& scene) {
  const std::string same = "resume with the scene (and --set overrides) of the run that wrote the checkpoint";
  if (!in.has("coupling.substeps"))
    in.fail(std::string("it holds no coupled state (") + (in.has("liquid.nodes") ? "a liquid" : "a DEM") +
                " scene's run wrote it)",
            "resume a scene of liquid and grains from a checkpoint its own run wrote (<out>/checkpoints/checkpoint.gfc)");
  if (in.value<double>("clock.dt") != scene.liquid.dt)
    in.fail("it was written with run.dt = " + short_number(in.value<double>("clock.dt")) + " s, the scene has " +
                short_number(scene.liquid.dt) + " s",
            "resume with the same run.dt: a checkpoint continues a run, it does not change its step");
  const auto k = in.value<std::int64_t>("coupling.substeps");
  if (k != scene.coupling.substeps)
    in.fail("it was written with " + std::to_string(k) + " DEM sub-steps per liquid step, the scene has " +
                std::to_string(scene.coupling.substeps),
            same + " (coupling.substeps, or the contact law that computes them)");
  restore_clock(in, world.clock);
  restore_dem_rows(in, world, scene.dem);
  restore_liquid_nodes(in, world, scene.liquid);
}

}  // namespace gf
