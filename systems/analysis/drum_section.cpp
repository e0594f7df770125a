#include "systems/analysis/drum_section.hpp"

#include <cmath>

namespace gf {

DrumSection drum_section(const Wall& cylinder, const Vec3d& gravity) {
  DrumSection s;
  s.center = cylinder.cur_center;
  s.axis = (1.0 / std::sqrt(dot(cylinder.cur_axis, cylinder.cur_axis))) * cylinder.cur_axis;
  s.radius = cylinder.radius;
  // Up: -g with its axial part removed. Fallback: the world axis least aligned with the drum axis.
  Vec3d up = -gravity;
  up = up - dot(up, s.axis) * s.axis;
  if (!(dot(up, up) > 1e-12 * dot(gravity, gravity)) || dot(up, up) == 0.0) {
    const double ax = std::abs(s.axis.x), ay = std::abs(s.axis.y), az = std::abs(s.axis.z);
    const Vec3d pick = (ay <= ax && ay <= az) ? Vec3d{0, 1, 0} : (ax <= az ? Vec3d{1, 0, 0} : Vec3d{0, 0, 1});
    up = pick - dot(pick, s.axis) * s.axis;
  }
  s.up = (1.0 / std::sqrt(dot(up, up))) * up;
  s.right = cross(s.up, s.axis);
  return s;
}

std::optional<std::size_t> find_drum(const Walls& walls) {
  std::optional<std::size_t> first;
  for (std::size_t w = 0; w < walls.list.size(); ++w) {
    if (walls.list[w].kind != Wall::Kind::CylinderInner) continue;
    if (walls.list[w].omega != 0.0) return w;
    if (!first) first = w;
  }
  return first;
}

}  // namespace gf
