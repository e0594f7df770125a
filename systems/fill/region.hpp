// A placement region for fills: a box or a (possibly height-limited) cylinder.
// Plain data so that a scene loader can fill it in field by field; problem() says what is wrong
// with it in words, so the loader can attach the scene file, line and key.
#pragma once

#include <array>
#include <limits>
#include <string>

namespace gf {

struct Region {
  enum class Kind { Box, Cylinder };
  Kind kind = Kind::Box;

  // Box: axis-aligned, lo < hi componentwise (m).
  std::array<double, 3> lo{0.0, 0.0, 0.0};
  std::array<double, 3> hi{0.0, 0.0, 0.0};

  // Cylinder: `axis` is a unit vector through `center`; the cylinder reaches length/2 to each side
  // of the centre along it (m).
  std::array<double, 3> center{0.0, 0.0, 0.0};
  std::array<double, 3> axis{0.0, 0.0, 1.0};
  double radius = 0.0;
  double length = 0.0;

  // Cylinder only: keeps the points whose height (x - center) . up is <= max_height, so that
  // "the lower half of a drum" (max_height = 0) is a region. `up` is a unit vector; a scene loader
  // sets it to -gravity/|gravity|. The default +y matches the seed scenes, whose gravity is along -y.
  // A box is cut by lowering hi instead, which is why a box ignores these two fields
  // (problem() reports a finite max_height on a box rather than dropping it silently).
  std::array<double, 3> up{0.0, 1.0, 0.0};
  double max_height = std::numeric_limits<double>::infinity();

  static Region box(const std::array<double, 3>& lo, const std::array<double, 3>& hi);
  // Normalises axis and up, so callers may pass any non-zero direction.
  static Region cylinder(const std::array<double, 3>& center, const std::array<double, 3>& axis,
                         double radius, double length,
                         double max_height = std::numeric_limits<double>::infinity(),
                         const std::array<double, 3>& up = {0.0, 1.0, 0.0});

  // m^3; for a height-limited cylinder the exact volume of the cylinder cut by the plane.
  double volume() const;
  // True when the whole sphere (centre p, radius r) lies inside the region.
  bool contains_sphere(const std::array<double, 3>& p, double r) const;
  // An axis-aligned box holding the region (tight for a box and an uncut cylinder; a cut
  // cylinder is only trimmed when `up` is a coordinate direction).
  std::array<double, 3> bbox_lo() const;
  std::array<double, 3> bbox_hi() const;

  // Empty when the region is usable; otherwise what is wrong and how to fix it.
  std::string problem() const;
};

}  // namespace gf
