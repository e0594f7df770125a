// The state of a liquid (MPS) run in a checkpoint (engine/checkpoint_file): every FluidNodes column in row order
// (the pressure is the next solve's starting guess), the neighbour list with its reference positions (it is
// rebuilt only when a node has moved half the skin since them), the last step's diagnostics (the series reads
// them) and the clock. Restoring all of it, rather than re-deriving any of it, makes a resumed run bit-identical
// to an uninterrupted one.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"
#include "systems/mps/liquid_scene.hpp"

namespace gf {

void save_liquid_state(CheckpointWriter& out, World& world, const LiquidScene& scene);

// Replaces the world's state by the checkpoint's. The world must have been built from the same scene (same
// dimension, spacing, time step and node lattice): anything else, or a checkpoint of a DEM scene, is a
// CheckpointError naming the file, what differs and the fix.
void restore_liquid_state(const CheckpointReader& in, World& world, const LiquidScene& scene);

// The same without the clock, for a checkpoint that holds more than the liquid (a coupled run's).
void save_liquid_nodes(CheckpointWriter& out, World& world, const LiquidScene& scene);
void restore_liquid_nodes(const CheckpointReader& in, World& world, const LiquidScene& scene);

}  // namespace gf
