// A wall's translation, on top of its rotation (walls.hpp): the reference geometry is carried by an
// offset d(t) whose rate is the surface's translational velocity. Three motions add:
//  - a constant velocity v:                         d = v t;
//  - a sinusoidal vibration of amplitude A (a vector, m), frequency f (Hz) and phase phi (rad):
//                                                   d = A sin(2 pi f t + phi) - A sin(phi);
//  - a prescribed velocity table (time, vx, vy, vz), linear between its rows and held at the last
//    row's velocity after it:                       d = the integral of the table's velocity from 0.
// A point X of the reference geometry is at o + d(t) + R(omega t)(X - o) (o the rotation point), and
// moves at d'(t) + omega x (x - o - d(t)). While a fill settles no wall moves, and the clock restarts
// at 0 after it, so every motion starts from the reference geometry.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "systems/contact/vec3.hpp"

namespace gf {

class SceneNode;
using Vec3d = V3<double>;

struct WallMotion {
  Vec3d velocity{0, 0, 0};   // m/s
  Vec3d amplitude{0, 0, 0};  // m
  double frequency = 0.0;    // Hz
  double phase = 0.0;        // rad
  // The velocity table: times (s, from 0, increasing), velocities (m/s) and the offset reached at
  // each row (the table's integral, filled by set_table).
  std::vector<double> table_time;
  std::vector<Vec3d> table_velocity, table_offset;

  bool moves() const;
  Vec3d offset(double t) const;  // d(t), m
  Vec3d rate(double t) const;    // d'(t), m/s
  // The largest |d'(t)| over all t, m/s (for the step check).
  double fastest() const;
  // Sets the table and its running integral; times must start at 0 and increase.
  void set_table(std::vector<double> time, std::vector<Vec3d> velocity);
};

// A wall's motion from its [[wall]] table (keys velocity, vibration_amplitude, vibration_frequency,
// vibration_phase, velocity_file), refusing a table file that cannot be read, naming its line.
WallMotion read_wall_motion(const SceneNode& w);
// Whether the table gives any of those keys.
bool has_wall_motion(const SceneNode& w);

// A velocity table file: one row "time, vx, vy, vz" per line (s, m/s), a header line and lines
// starting with '#' skipped. SceneError naming the file, the line and the fix.
void read_velocity_table(const std::filesystem::path& file, std::vector<double>& time, std::vector<Vec3d>& velocity);

}  // namespace gf
