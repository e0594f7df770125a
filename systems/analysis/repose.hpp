// The angle of repose of a heap, or the slopes of a crater, from grain positions: the free
// surface's height against horizontal distance, fitted by a straight line on each flank.
//
// Surface. The horizontal coordinate s is cut into columns of width `column` (m). Two geometries:
//   radial  a conical heap about a vertical axis through `centre`: s is the distance from the axis,
//           and the heap has one flank, from its top at the axis outwards;
//   planar  a ridge or a valley along a horizontal direction: s is the coordinate along `across`,
//           a horizontal unit vector across the ridge, and there are two flanks, one each side of
//           the crest (a heap) or of the bottom (a crater, the heap left in a flat-bottomed hopper
//           around its outlet).
// Height is along `up` (against gravity). A column's surface is the `rank`-th highest grain top
// (up . x + r) in it, so that one or two grains perched on the surface or in flight do not lift
// it (the pattern classifier's free surface is found the same way); columns with fewer than `rank`
// grains are left out.
//
// Flanks. From the extreme column (the highest for a heap, the lowest for a crater) outwards to the
// last column: the flank's height range runs from its foot (its lowest column for a heap, its
// highest for a crater) to the extreme. The fit is least squares of height against s over the
// flank's columns whose height lies between `lower` and `upper` of the way along that range
// (0.15 and 0.85 by default): the rounded crest and the toe, which curve, are left out, as in the
// usual reading of a heap's static angle from its profile. angle = atan |slope|, in radians.
//
// A heap that is not one cone or one ridge (several crests, a surface broken by walls) is not what
// this measures; the fitted columns are reported so that a caller can tell.
#pragma once

#include <cstddef>
#include <limits>
#include <span>

#include "systems/contact/vec3.hpp"

namespace gf {

struct ReposeGrains {
  std::span<const double> x, y, z, r;  // m
};

struct ReposeSettings {
  double column = 0.0;   // m, width of a column of s (> 0; two to four grain diameters is usual)
  int rank = 3;          // the surface is the rank-th highest grain top of a column (>= 1)
  double lower = 0.15;   // fraction of the flank's height range below which columns are left out
  double upper = 0.85;   // fraction above which columns are left out (0 <= lower < upper <= 1)
  int min_columns = 3;   // fewer columns in the fit: NaN
};

struct ReposeFlank {
  double angle = std::numeric_limits<double>::quiet_NaN();  // rad, atan |slope|
  double slope = std::numeric_limits<double>::quiet_NaN();  // d height / d s
  std::size_t columns = 0;                                  // columns fitted
  double s_from = 0.0, s_to = 0.0;                          // m, the fitted columns' span of s
};

struct Repose {
  // radial: `first` is the one flank (from the axis outwards); planar: `first` the flank at smaller
  // s, `second` the one at larger s.
  ReposeFlank first, second;
  double extreme_height = std::numeric_limits<double>::quiet_NaN();  // m, the crest's (or bottom's) surface
  double extreme_s = std::numeric_limits<double>::quiet_NaN();       // m, its column's centre
};

// std::invalid_argument for columns that differ in length, a zero `up`, or settings out of range.
Repose repose_radial(const ReposeGrains& grains, const V3<double>& centre, const V3<double>& up,
                     const ReposeSettings& settings);
// `across` is made horizontal (its part along `up` removed) and unit; std::invalid_argument if none is left.
Repose repose_planar(const ReposeGrains& grains, const V3<double>& across, const V3<double>& up,
                     const ReposeSettings& settings, bool crater = false);

}  // namespace gf
