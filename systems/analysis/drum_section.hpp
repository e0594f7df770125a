// The cross-section of a drum seen along its axis: a 2-D frame in the plane perpendicular to the
// axis, with "up" against gravity, so pictures and the pattern classifier both show the bed at the
// bottom as an observer in the lab sees it (the drum turns, the frame does not).
#pragma once

#include <optional>

#include "systems/walls/walls.hpp"

namespace gf {

struct DrumSection {
  Vec3d center{0, 0, 0};  // a point on the axis, m
  Vec3d axis{0, 0, 1};    // unit, pointing at the viewer
  Vec3d right{1, 0, 0};   // unit, in the section plane
  Vec3d up{0, 1, 0};      // unit, in the section plane, against gravity; right = up x axis
  double radius = 0;      // m, inner radius of the drum

  // Section-plane coordinates (m) of a point: along `right` and along `up`, from the axis.
  double u(double x, double y, double z) const {
    return (x - center.x) * right.x + (y - center.y) * right.y + (z - center.z) * right.z;
  }
  double v(double x, double y, double z) const {
    return (x - center.x) * up.x + (y - center.y) * up.y + (z - center.z) * up.z;
  }
  // Distance along the axis towards the viewer (m): larger is nearer.
  double depth(double x, double y, double z) const {
    return (x - center.x) * axis.x + (y - center.y) * axis.y + (z - center.z) * axis.z;
  }
};

// The frame of a cylindrical wall (current geometry). `gravity` (m/s^2) sets "up"; when it is
// zero or along the axis, any direction perpendicular to the axis is taken.
DrumSection drum_section(const Wall& cylinder, const Vec3d& gravity);

// Index of the wall a drum picture or pattern refers to: the first rotating inner cylinder, else the
// first inner cylinder; none if the scene has no cylinder.
std::optional<std::size_t> find_drum(const Walls& walls);

}  // namespace gf
