// The periodic images in a checkpoint, saved and restored by the periodic system itself: each image
// row's owner and shift. A scene without periodic faces writes nothing, and a checkpoint is refused
// by name when it was written with periodic faces and the scene now has none, or the reverse.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/grains.hpp"
#include "systems/periodic/periodic_images.hpp"

namespace gf {

void save_periodic_images(CheckpointWriter& out, const PeriodicImages& im);
// After the grain rows: the images must match the ghost rows and point at owned rows.
void restore_periodic_images(const CheckpointReader& in, PeriodicImages& im, const Grains& g);

}  // namespace gf
