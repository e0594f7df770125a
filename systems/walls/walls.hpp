// Walls: analytic geometry outside the particle grid (planes, the inner surface of a cylinder).
// Any wall may rotate about an axis at a constant rate; its surface velocity at the contact point
// enters the relative velocity, and its angular velocity the relative rolling rate. A drum is a
// cylinder with two flat end walls sharing one rotation.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "engine/column.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

using Vec3d = V3<double>;

struct Wall {
  enum class Kind { Plane, CylinderInner };
  Kind kind = Kind::Plane;
  std::string name;
  // Reference geometry, at rotation angle 0.
  Vec3d point{0, 0, 0}, normal{0, 0, 1};  // plane: a point on it and the unit normal into the domain
  Vec3d center{0, 0, 0}, axis{0, 0, 1};   // cylinder: a point on the axis and the unit axis
  double radius = 0.0;                    // cylinder radius, m
  // Rotation of the wall as a rigid body.
  Vec3d rot_point{0, 0, 0}, rot_axis{0, 0, 1};
  double omega = 0.0;  // rad/s
  // Geometry at the current angle (rotated reference geometry).
  Vec3d cur_point{0, 0, 0}, cur_normal{0, 0, 1}, cur_center{0, 0, 0}, cur_axis{0, 0, 1};
};

struct Walls {
  std::vector<Wall> list;
  bool rotation_enabled = true;  // off while a fill settles
  // Sets every wall's current geometry for time t (angle omega t, or 0 when rotation is off).
  void place(double t);
  double angle(std::size_t w, double t) const { return rotation_enabled ? list[w].omega * t : 0.0; }
};

// Signed distance from a point to the wall surface, positive inside the domain, with the unit
// vector from the point towards the surface. Uses the current geometry.
double wall_gap(const Wall& w, const Vec3d& p, Vec3d& towards);

Vec3d rotate_about(const Vec3d& v, const Vec3d& axis, double angle);

// Contact history of each row against each wall: six columns per wall (spring, rolling angle),
// and per wall a column that is 1 where the row touched the wall at the last evaluation, so the
// kernels skip rows far from a wall without reading their springs.
// The springs of one row against one wall: tangential (sx, sy, sz, m) then rolling (rx, ry, rz,
// rad), padded to a cache line so that the law reads a row's springs as one line.
struct alignas(64) WallSprings {
  double s[8];
};

struct WallHistory {
  std::vector<Column<WallSprings>> springs;   // 1 per wall
  std::vector<Column<std::uint8_t>> active;   // 1 per wall: touching at the last evaluation
  void shape(std::size_t walls, std::size_t rows) {
    springs.resize(walls);
    active.resize(walls);
    for (auto& c : springs) c.resize(rows);
    for (auto& c : active) c.resize(rows);
  }
  template <class F>
  void visit_columns(F&& f) {
    for (auto& c : springs) f(c);
    for (auto& c : active) f(c);
  }
};

}  // namespace gf
