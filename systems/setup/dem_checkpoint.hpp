// The state of a DEM run in a checkpoint: every grain column in row order (attached components
// included), the neighbour list and the contact springs aligned with it, the broadphase's
// reference positions and counters, and the clock. Restoring all of it, rather than re-deriving
// any of it, is what makes a resumed run bit-identical to an uninterrupted one: the row order,
// the pair order and hence every floating-point sum are the same.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

void save_dem_state(CheckpointWriter& out, World& world, const DemScene& scene);

// Replaces the world's state by the checkpoint's. The world must have been built from the same
// scene (same grain count, species, walls, dt and skin): anything else is a CheckpointError naming
// the file, what differs and the fix.
void restore_dem_state(const CheckpointReader& in, World& world, const DemScene& scene);

// The same without the clock, for a checkpoint that holds more than the grains (a coupled run's, whose
// clock is the liquid's step): restore_dem_rows places the walls at the world's clock, so restore the
// clock first.
void save_dem_rows(CheckpointWriter& out, World& world, const DemScene& scene);
void restore_dem_rows(const CheckpointReader& in, World& world, const DemScene& scene);

}  // namespace gf
