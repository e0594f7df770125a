// A [[species]]' `diameter`: a number (one size) or a table that names a size distribution
// (systems/fill/size_distribution.hpp), read through the key table kDiameterFields.
#pragma once

#include "engine/scene.hpp"
#include "systems/fill/size_distribution.hpp"

namespace gf {

// Reads `diameter` of a [[species]] table; a SceneError names the key, the cause and the fix.
SizeDistribution read_species_size(const SceneNode& species);

}  // namespace gf
