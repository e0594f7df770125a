// The angle of repose of a heap of composite grains (systems/analysis/repose.hpp on their members).
// Each member of a moving body stands for one grain of the repose measure: its bounding centre places
// it in a column, and its top is the highest point of its dilated core along `up` (the highest core
// vertex plus r), so the surface follows the members' real outlines, not their bounding spheres.
// A region (optional) keeps the members whose centre lies in an axis-aligned box: a band across a
// square hopper's outlet, where the walls' ledges beside it would otherwise set the columns' tops.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "systems/analysis/repose.hpp"
#include "systems/bodies/bodies.hpp"

namespace gf {

struct ReposeSpec {
  enum class Geometry { heap, ridge, crater };
  std::string name;
  Geometry geometry = Geometry::heap;
  V3<double> centre{0, 0, 0};  // m, a point on a heap's axis (heap)
  V3<double> across{1, 0, 0};  // the horizontal direction across a ridge or crater (ridge, crater)
  ReposeSettings settings;
  bool has_region = false;
  std::array<double, 3> lo{}, hi{};  // m, the region's box
};

// The moving bodies' members as repose grains: x, y, z their bounding centres, r the height of their
// top above that centre along the unit vector `up`. Members outside the spec's region are left out.
struct MemberTops {
  std::vector<double> x, y, z, r;
  ReposeGrains view() const { return {x, y, z, r}; }
};
MemberTops member_tops(const Bodies& bodies, const Members& members, const V3<double>& up, const ReposeSpec& spec);

// The repose of the spec's heap, ridge or crater; throws as repose_radial / repose_planar.
Repose body_repose(const Bodies& bodies, const Members& members, const V3<double>& up, const ReposeSpec& spec);

}  // namespace gf
