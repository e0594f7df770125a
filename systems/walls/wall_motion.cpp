#include "systems/walls/wall_motion.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string_view>

#include "engine/field_table.hpp"
#include "engine/read_file.hpp"
#include "engine/scene.hpp"
#include "engine/user_text.hpp"
#include "systems/walls/wall_fields.hpp"

namespace gf {

namespace {

constexpr std::size_t kMaxTableBytes = std::size_t(1) << 28;  // 256 MB: millions of rows, never all memory

double magnitude(const Vec3d& v) { return std::sqrt(dot(v, v)); }

[[noreturn]] void fail_table(const std::filesystem::path& file, std::size_t line, const std::string& problem,
                             const std::string& fix) {
  std::string msg = shown_path(file.string());
  if (line > 0) msg += ":" + std::to_string(line);
  throw SceneError(msg + ": " + problem + ". Fix: " + fix);
}

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// The fields of a line split at commas, each parsed whole as a finite number; false if one is not.
bool parse_row(std::string_view line, std::vector<double>& out) {
  out.clear();
  while (true) {
    const std::size_t comma = line.find(',');
    const std::string_view f = trim_blanks(line.substr(0, comma));
    double v = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc{} || end != f.data() + f.size() || !std::isfinite(v)) return false;
    out.push_back(v);
    if (comma == std::string_view::npos) return true;
    line.remove_prefix(comma + 1);
  }
}

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
  std::string data;
  FileProblem why;
  if (!read_regular_file(file, kMaxTableBytes, data, why)) fail_table(file, 0, "velocity table: " + why.problem, why.fix);
  time.clear();
  velocity.clear();
  std::vector<double> row;
  std::size_t line_no = 0;
  bool header_seen = false;
  for (std::size_t at = 0; at < data.size();) {
    const std::size_t end = std::min(data.find('\n', at), data.size());
    const std::string_view line = trim_blanks(std::string_view(data).substr(at, end - at));
    at = end + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    if (!parse_row(line, row)) {
      if (!header_seen && time.empty()) {  // a header line of names
        header_seen = true;
        continue;
      }
      fail_table(file, line_no, "velocity table: the row " + quoted(line) + " is not four numbers",
                 "give each row as time, vx, vy, vz (s, m/s), separated by commas");
    }
    if (row.size() != 4)
      fail_table(file, line_no, "velocity table: the row has " + std::to_string(row.size()) + " numbers, not 4",
                 "give each row as time, vx, vy, vz (s, m/s)");
    if (time.empty() && row[0] != 0.0)
      fail_table(file, line_no, "velocity table: the first row is at " + number_text(row[0]) + " s, not at 0",
                 "start the table at time 0 (the run's clock after settling)");
    if (!time.empty() && !(row[0] > time.back()))
      fail_table(file, line_no, "velocity table: time " + number_text(row[0]) + " s does not follow " +
                                    number_text(time.back()) + " s",
                 "list the rows in increasing time, each time once");
    for (int c = 1; c < 4; ++c)
      if (std::abs(row[c]) > range::speed.hi)
        fail_table(file, line_no, "velocity table: speed " + number_text(row[c]) + " m/s is above " +
                                      number_text(range::speed.hi) + " m/s",
                   "give velocities in m/s (is it in mm/s?)");
    time.push_back(row[0]);
    velocity.push_back({row[1], row[2], row[3]});
  }
  if (time.empty()) fail_table(file, 0, "velocity table: the file has no rows", "give rows of time, vx, vy, vz from time 0");
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
      // "<file>:<line>: <problem>. Fix: <fix>" as the scene's message at the key, its fix kept.
      const std::string m = e.what();
      const std::size_t at = m.rfind(". Fix: ");
      if (at == std::string::npos) w.fail("velocity_file", m, "correct the file, or the path (relative to the scene file)");
      w.fail("velocity_file", m.substr(0, at), m.substr(at + 7));
    }
    m.set_table(std::move(t), std::move(v));
  }
  return m;
}

}  // namespace gf
