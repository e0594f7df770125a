#include "systems/walls/wall_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string_view>

#include "engine/field_table.hpp"
#include "engine/number_table.hpp"
#include "engine/scene.hpp"
#include "engine/user_text.hpp"
#include "systems/walls/wall_fields.hpp"

namespace gf {

namespace {

double magnitude(const Vec3d& v) { return std::sqrt(dot(v, v)); }

}  // namespace

bool WallMotion::moves() const {
  return magnitude(velocity) > 0.0 || (magnitude(amplitude) > 0.0 && frequency > 0.0) || !table_time.empty();
}

Vec3d WallMotion::offset(double t) const {
  Vec3d d = t * velocity;
  if (frequency > 0.0) {
    const double w = 2.0 * std::numbers::pi * frequency;
    d = d + (std::sin(w * t + phase) - std::sin(phase)) * amplitude;
  }
  if (table_time.empty() || t <= 0.0) return d;
  const auto k = static_cast<std::size_t>(std::upper_bound(table_time.begin(), table_time.end(), t) - table_time.begin()) - 1;
  const double tau = t - table_time[k];
  d = d + table_offset[k] + tau * table_velocity[k];
  if (k + 1 < table_time.size())
    d = d + (0.5 * tau * tau / (table_time[k + 1] - table_time[k])) * (table_velocity[k + 1] - table_velocity[k]);
  return d;
}

Vec3d WallMotion::rate(double t) const {
  Vec3d v = velocity;
  if (frequency > 0.0) {
    const double w = 2.0 * std::numbers::pi * frequency;
    v = v + (w * std::cos(w * t + phase)) * amplitude;
  }
  if (table_time.empty()) return v;
  if (t <= 0.0) return v + table_velocity.front();
  const auto k = static_cast<std::size_t>(std::upper_bound(table_time.begin(), table_time.end(), t) - table_time.begin()) - 1;
  if (k + 1 == table_time.size()) return v + table_velocity[k];
  const double s = (t - table_time[k]) / (table_time[k + 1] - table_time[k]);
  return v + table_velocity[k] + s * (table_velocity[k + 1] - table_velocity[k]);
}

double WallMotion::fastest() const {
  double table = 0.0;
  for (const Vec3d& v : table_velocity) table = std::max(table, magnitude(v));
  return magnitude(velocity) + 2.0 * std::numbers::pi * frequency * magnitude(amplitude) + table;
}

void WallMotion::set_table(std::vector<double> time, std::vector<Vec3d> velocity_rows) {
  table_time = std::move(time);
  table_velocity = std::move(velocity_rows);
  table_offset.assign(table_time.size(), Vec3d{0, 0, 0});
  for (std::size_t k = 1; k < table_time.size(); ++k)
    table_offset[k] = table_offset[k - 1] +
                      (0.5 * (table_time[k] - table_time[k - 1])) * (table_velocity[k - 1] + table_velocity[k]);
}

void read_velocity_table(const std::filesystem::path& file, std::vector<double>& time, std::vector<Vec3d>& velocity) {
  time.clear();
  velocity.clear();
  for (const NumberRow& r : read_number_table(file, 4, "velocity table", "time, vx, vy, vz (s, m/s)")) {
    const std::vector<double>& row = r.values;
    if (time.empty() && row[0] != 0.0)
      fail_number_table(file, r.line, "velocity table: the first row is at " + number_text(row[0]) + " s, not at 0",
                        "start the table at time 0 (the run's clock after settling)");
    if (!time.empty() && !(row[0] > time.back()))
      fail_number_table(file, r.line, "velocity table: time " + number_text(row[0]) + " s does not follow " +
                                          number_text(time.back()) + " s",
                        "list the rows in increasing time, each time once");
    for (int c = 1; c < 4; ++c)
      if (std::abs(row[c]) > range::speed.hi)
        fail_number_table(file, r.line, "velocity table: speed " + number_text(row[c]) + " m/s is above " +
                                            number_text(range::speed.hi) + " m/s",
                          "give velocities in m/s (is it in mm/s?)");
    time.push_back(row[0]);
    velocity.push_back({row[1], row[2], row[3]});
  }
  if (time.empty()) fail_number_table(file, 0, "velocity table: the file has no rows", "give rows of time, vx, vy, vz from time 0");
}

bool has_wall_motion(const SceneNode& w) {
  for (const char* k : {"velocity", "vibration_amplitude", "vibration_frequency", "vibration_phase", "velocity_file"})
    if (w.has(k)) return true;
  return false;
}

WallMotion read_wall_motion(const SceneNode& w) {
  WallMotion m;
  const auto vec = [&](std::string_view key) {
    const std::array<double, 3> a = w.get_vec3(kWallFields.field(key).key, {0, 0, 0});
    const Vec3d v{a[0], a[1], a[2]};
    if (magnitude(v) > kWallFields.field(key).range.hi)
      w.fail(key, "its length " + short_number(magnitude(v)) + " is above " + short_number(kWallFields.field(key).range.hi),
             key == "velocity" ? "give the velocity in m/s (is it in mm/s?)" : "give the amplitude in m (is it in mm?)");
    return v;
  };
  m.velocity = vec("velocity");
  m.amplitude = vec("vibration_amplitude");
  m.frequency = read_number(w, kWallFields.field("vibration_frequency"));
  m.phase = read_number(w, kWallFields.field("vibration_phase"));
  if (magnitude(m.amplitude) > 0.0 && m.frequency == 0.0)
    w.fail("vibration_frequency", "the wall has a vibration amplitude but no frequency",
           "give vibration_frequency (Hz), or remove vibration_amplitude");
  if (m.frequency > 0.0 && magnitude(m.amplitude) == 0.0)
    w.fail("vibration_amplitude", "the wall has a vibration frequency but no amplitude",
           "give vibration_amplitude = [x, y, z] (m)");
  if (w.has("velocity_file")) {
    std::vector<double> t;
    std::vector<Vec3d> v;
    try {
      read_velocity_table(w.doc().resolve(w.get_string("velocity_file")), t, v);
    } catch (const SceneError& e) {
      fail_at_key(w, "velocity_file", e);
    }
    m.set_table(std::move(t), std::move(v));
  }
  return m;
}

}  // namespace gf
