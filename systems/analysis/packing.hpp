// The packing (solid volume) fraction of composite grains in a box, by sampling: the box is cut into
// cubic voxels of edge h, and a voxel is solid when its centre lies in some moving body's member
// (within the member's dilation radius of its convex core: ConvexCore::dilated_contains, the test
// the mass properties use). The fraction is the solid voxels over all voxels. Every voxel the grains'
// surfaces cut is the only error, so it falls with h: at most the voxels within (sqrt 3 / 2) h of the
// surfaces, a relative error of about the grains' surface over their volume times h.
// The seed's packing case reads the fraction in the bed's interior, away from walls and the top
// surface, which is what the box is for.
#pragma once

#include <array>
#include <cstddef>

#include "systems/bodies/bodies.hpp"

namespace gf {

struct PackingFraction {
  double fraction = 0.0;   // solid voxels / voxels
  std::size_t voxels = 0;  // in the box
  std::size_t solid = 0;
};

// std::invalid_argument for a box with hi <= lo, a voxel edge not positive and finite, or more than
// 2^30 voxels (a finer sampling than that is a mistake in h).
PackingFraction packing_fraction(const Bodies& bodies, const Members& members, const std::array<double, 3>& lo,
                                 const std::array<double, 3>& hi, double h);

}  // namespace gf
