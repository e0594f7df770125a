// Walls: analytic geometry outside the particle grid (planes, the inner surface of a cylinder).
// Any wall may rotate about an axis at a constant rate and translate (wall_motion.hpp: a velocity,
// a vibration, a velocity table); its surface velocity at the contact point enters the relative
// velocity, and its angular velocity the relative rolling rate. A drum is a cylinder with two flat
// end walls sharing one rotation (and one translation); a box's six faces share one translation.
//
// Loads. Each contact evaluation of a full step adds, per wall, the force F_i and the moment
// (x_i - o) x F_i + T_i of its contacts on the grains (x_i the grain's centre, T_i the torque about
// it, o the wall's current rotation point): by Newton's third law the wall receives their negatives,
// and its drive supplies the power F_i . v + ((x_i - o) x F_i + T_i) . omega (v, omega the wall's
// translational and angular velocity). WallLoads keeps their sums over the run's full steps; a
// series row reports the mean over its interval from them (wall_loads_csv.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/column.hpp"
#include "systems/contact/vec3.hpp"
#include "systems/walls/wall_motion.hpp"

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
  WallMotion motion;    // translation
  // For drawing only (wall_surfaces.hpp): a plane's polygon at its reference place (a box's face, a
  // drum's end; empty: drawn across the scene), a cylinder's length (a drum's; 0: across the scene).
  std::vector<Vec3d> outline;
  double length = 0.0;
  // Geometry at the current angle and offset; the rotation point carried by the offset, the
  // translational velocity and the angular velocity (zero while motion is off).
  Vec3d cur_point{0, 0, 0}, cur_normal{0, 0, 1}, cur_center{0, 0, 0}, cur_axis{0, 0, 1};
  Vec3d cur_origin{0, 0, 0}, cur_velocity{0, 0, 0}, cur_spin{0, 0, 0};
};

// One wall's load on the grains (see above): of one evaluation, or summed over steps.
struct WallLoad {
  Vec3d force{0, 0, 0};   // sum of F_i, N
  Vec3d moment{0, 0, 0};  // sum of (x_i - o) x F_i + T_i, N m
  double power = 0.0;     // sum of the drive's power, W
};

struct WallLoads {
  std::vector<WallLoad> now;  // per wall: the last evaluation
  std::vector<WallLoad> sum;  // per wall: summed over the run's full steps (checkpointed)
  std::int64_t steps = 0;     // full steps summed
  void accumulate() {
    if (sum.size() != now.size()) sum.resize(now.size());
    for (std::size_t w = 0; w < now.size(); ++w) {
      sum[w].force = sum[w].force + now[w].force;
      sum[w].moment = sum[w].moment + now[w].moment;
      sum[w].power += now[w].power;
    }
    ++steps;
  }
};

// A WallLoad as its seven numbers in a flat array (force, moment, power), as checkpoints and messages
// between processes carry it, and back.
constexpr std::size_t kWallLoadNumbers = 7;
inline void append_wall_load(std::vector<double>& out, const WallLoad& l) {
  out.insert(out.end(), {l.force.x, l.force.y, l.force.z, l.moment.x, l.moment.y, l.moment.z, l.power});
}
inline WallLoad wall_load_of(const double* a) { return {{a[0], a[1], a[2]}, {a[3], a[4], a[5]}, a[6]}; }

class CheckpointWriter;
class CheckpointReader;
// A WallLoads' running sums in a checkpoint under `key`: seven numbers per wall, and the steps
// summed. A checkpoint of an older build has none: the sums restart, and the first row after it
// averages the steps since the resume.
void save_wall_loads(CheckpointWriter& out, const std::string& key, const WallLoads& l);
void restore_wall_loads(const CheckpointReader& in, const std::string& key, WallLoads& l);

// One wall's load of one evaluation from the sums of its contacts' forces and moments on the grains
// (six numbers), with the power at the wall's velocity and spin.
inline WallLoad wall_load(const double* sums, const Vec3d& velocity, const Vec3d& spin) {
  WallLoad l;
  l.force = {sums[0], sums[1], sums[2]};
  l.moment = {sums[3], sums[4], sums[5]};
  l.power = dot(l.force, velocity) + dot(l.moment, spin);
  return l;
}

// Each wall's load of one evaluation from the sums of its contacts' forces and moments (six numbers a
// wall), at the walls' velocities and spins.
inline void set_wall_loads(const std::vector<double>& sums, std::vector<WallLoad>& out,
                           const std::vector<Vec3d>& velocity, const std::vector<Vec3d>& spin) {
  out.resize(velocity.size());
  for (std::size_t w = 0; w < out.size(); ++w) out[w] = wall_load(&sums[6 * w], velocity[w], spin[w]);
}

struct Walls {
  std::vector<Wall> list;
  bool rotation_enabled = true;  // rotation and translation: off while a fill settles
  WallLoads loads;               // of the analytic walls
  // Sets every wall's current geometry for time t (angle omega t and offset d(t), or none when
  // motion is off), and its translational velocity for time t - lag: the contact laws see the
  // grains' velocities of the half-step (kick, drift, forces, kick), half a step before their
  // positions, and a vibrating wall's velocity taken at the positions' time instead adds a damping
  // force of c a dt / 2 in phase with its acceleration (1.9 % of a grain's weight on a floor at
  // Gamma = 1 with seed 000's springs and dt = 1e-5 s; wall_motion_test).
  void place(double t, double lag = 0.0);
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
