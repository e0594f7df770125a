// The state of a run of composite grains in a checkpoint: every Bodies column in row order (pose,
// velocities, loads, motion: fixed and removed bodies included), the members' world centres, the
// member-pair list with the law's constants, the springs of member pairs and of (member, plane)
// pairs, the list's reference centres and counters, and the clock. As for grains
// (dem_checkpoint.hpp), restoring all of it rather than re-deriving any of it makes a resumed run
// bit-identical to an uninterrupted one.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

void save_body_state(CheckpointWriter& out, World& world, const DemScene& scene);

// Replaces the bodies' state by the checkpoint's. The world must have been built from the same scene
// (same bodies, shapes, walls, law, dt and skin): anything else is a CheckpointError naming the
// file, what differs and the fix.
void restore_body_state(const CheckpointReader& in, World& world, const DemScene& scene);

}  // namespace gf
