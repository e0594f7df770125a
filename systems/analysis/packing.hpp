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
#include <string>
#include <vector>

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

// The packing of a poured bed, read as the seed's packing case reads it: in the bed's interior, away
// from the container's walls, its floor and its free surface, where those walls order the grains.
//   The bed: voxels of edge h (on a grid from the origin) over the moving members' bounding box; its lateral extent and its floor
//   are those of its solid voxels (grains resting on the walls reach them, so that is the container
//   to within a voxel). `up` (0, 1, 2) is the axis against gravity, `up_sign` (+1, -1) its direction.
//   The free surface: the mean over the interior's columns of the top of each column's highest solid
//   voxel (a column is a lateral voxel with all its layers).
//   The interior: inset `margin` from the bed's lateral extent on every side, from `margin` above the
//   floor to `margin` below the free surface (whole voxels: a voxel counts when its centre is in).
//   The whole bed: its full lateral extent from the floor to the free surface (the walls' loose layer
//   included, as a fill height read off a container would count it).
// Not valid (with the reason) when no moving body has members, or the bed is narrower or shallower
// than two margins and a voxel. Throws as packing_fraction for a bad h.
struct BedPacking {
  bool valid = false;
  std::string reason;                         // why not, when not valid
  double margin = 0;                          // m
  std::array<double, 3> voxel{};              // m, the edges used (h rounded to fit the box)
  double floor = 0, surface = 0;              // m, coordinates along `up` of the floor and the free surface
  std::array<double, 3> bed_lo{}, bed_hi{};   // m, the solid voxels' extent
  std::array<double, 3> lo{}, hi{};           // m, the interior region
  PackingFraction interior, whole;
  struct Layer {
    double height = 0;    // m, the voxel layer's centre above the floor
    double interior = 0;  // solid fraction of the layer within the interior's columns
    double whole = 0;     // solid fraction of the layer across the bed's full extent
  };
  std::vector<Layer> layers;  // from the floor to the bed's highest solid voxel
};
BedPacking bed_packing(const Bodies& bodies, const Members& members, int up, int up_sign, double margin, double h);

}  // namespace gf
