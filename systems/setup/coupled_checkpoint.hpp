// The state of a coupled run (a liquid with grains in it) in a checkpoint: the clock (the liquid's step),
// the sub-step count, the grains' rows (dem_checkpoint.hpp: every column, the liquid's force on each
// grain among them, the neighbour list and the springs) and the liquid's nodes (liquid_checkpoint.hpp:
// nodes, neighbour list, the drive's force and last mean). The coupling's shares and liquid fractions are
// not stored: every step recomputes them from the positions first. Restoring all of it makes a resumed
// run bit-identical to an uninterrupted one.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"
#include "systems/setup/coupled_scene.hpp"

namespace gf {

void save_coupled_state(CheckpointWriter& out, World& world, const CoupledScene& scene);

// Replaces the world's state by the checkpoint's. The world must have been built from the same scene;
// a checkpoint of another scene, a DEM or a liquid run's, another run.dt or sub-step count is a
// CheckpointError naming the file, what differs and the fix.
void restore_coupled_state(const CheckpointReader& in, World& world, const CoupledScene& scene);

}  // namespace gf
