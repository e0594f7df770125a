// Helpers shared by the test programs: a temporary folder, reading files back, stirring grains by id,
// small closed forms and formatters that several tests restate, and the results files that the
// README's tables are made from.
#pragma once

#include <atomic>
#include <chrono>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <cstdlib>
#include <system_error>
#include <vector>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "engine/grains.hpp"
#include "engine/scene.hpp"
#include "systems/analysis/drum_section.hpp"
#include "systems/contact/vec3.hpp"

namespace gf::test {

// A fresh folder under the temp directory, removed with everything in it on destruction. The name
// (grainflow_<stem>_<pid>_<steady clock tick>_<serial>) is unique across parallel test processes and
// within one, so runs in parallel or after a crash don't collide.
struct TempDir {
  std::filesystem::path path;

  explicit TempDir(const std::string& stem) {
    static std::atomic<int> serial{0};
    const auto tick = std::chrono::steady_clock::now().time_since_epoch().count();
    path = std::filesystem::temp_directory_path() /
           ("grainflow_" + stem + "_" + std::to_string(::getpid()) + "_" + std::to_string(tick) + "_" +
            std::to_string(++serial));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  // Writes `text` as is (binary) to the file `name` in the folder, replacing it; returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const std::filesystem::path p = path / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }
};

// The message of the SceneError that f() throws, or "" when it throws none.
template <class F>
std::string scene_error_of(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

// The whole file as bytes; "" if it cannot be opened.
inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The lines of `text`, without their '\n'.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) out.push_back(l);
  return out;
}

// The lines of a file; none if it cannot be opened.
inline std::vector<std::string> read_lines(const std::filesystem::path& p) { return lines_of(read_file(p)); }

// One CSV field: as it is, or in double quotes (quotes inside doubled) when it holds a comma, a quote
// or a line break.
inline std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A number for a results file, with `digits` significant digits (the stream's default notation); ""
// for NaN, which stands for "not applicable".
inline std::string csv_number(double v, int digits = 8) {
  if (std::isnan(v)) return "";
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

// Appends `row` (one CSV line, without its line break) to the file `file` in the folder that the
// environment variable GRAINFLOW_RESULTS names, writing the line `header` first when the file does not
// exist yet. Does nothing when GRAINFLOW_RESULTS is unset or empty. Tests that check a figure against a
// published or closed-form value call it where they assert, so that the README's result tables are made
// from what the tests measured (tools/readme/tables.py).
inline void record_result(const std::string& file, const std::string& header, const std::string& row) {
  const char* dir = std::getenv("GRAINFLOW_RESULTS");
  if (dir == nullptr || *dir == '\0') return;
  const std::filesystem::path p = std::filesystem::path(dir) / file;
  const bool fresh = !std::filesystem::exists(p);
  std::ofstream out(p, std::ios::app);
  if (!out) throw std::runtime_error("record_result: cannot append to " + p.string());
  if (fresh) out << header << "\n";
  out << row << "\n";
}

// How a row of analytic.csv states its error and tolerance: relative to the reference in percent,
// relative as a plain ratio, or absolute in the quantity's unit.
enum class ErrorKind { percent, relative, absolute };

// One figure a contact or integrator test checks against a closed form (studies/contact/results/analytic.csv,
// the README's table "Contact physics against analytic values"). `closed_form` is the reference as
// the README writes it (or "conserved", "identical"); `reference` its value and `measured` the
// engine's, NaN where the check is on an error alone (a drift, a difference); `error` is the number
// the test compares with `tolerance`, both in the unit `kind` names.
struct AnalyticCheck {
  std::string case_name, quantity, closed_form;
  double reference = std::numeric_limits<double>::quiet_NaN();
  double measured = std::numeric_limits<double>::quiet_NaN();
  double error = 0.0;
  ErrorKind kind = ErrorKind::percent;
  double tolerance = 0.0;
};

// Appends `c` to analytic.csv when GRAINFLOW_RESULTS names a folder.
inline void record_analytic(const AnalyticCheck& c) {
  const char* kind = c.kind == ErrorKind::percent ? "relative %" : c.kind == ErrorKind::relative ? "relative" : "absolute";
  record_result("analytic.csv", "case,quantity,closed_form,reference,measured,error,error_kind,tolerance",
                csv_field(c.case_name) + "," + csv_field(c.quantity) + "," + csv_field(c.closed_form) + "," +
                    csv_number(c.reference, 10) + "," + csv_number(c.measured, 10) + "," + csv_number(c.error, 4) +
                    "," + kind + "," + csv_number(c.tolerance, 4));
}

// The cross-section frame of a drum of `radius` (m) about the z axis through the origin, gravity
// along -y: the frame the pattern and mixing tests place their synthetic beds in.
inline DrumSection drum_section_z(double radius) {
  Wall w;
  w.kind = Wall::Kind::CylinderInner;
  w.cur_center = {0, 0, 0};
  w.cur_axis = {0, 0, 1};
  w.radius = radius;
  return drum_section(w, {0, -9.81, 0});
}

// Random velocities (each component uniform in [-max_speed, max_speed]) and spins (uniform in
// [-max_spin, max_spin]) drawn in id order, so that what a grain gets does not depend on its row.
// Ids must be 0 .. n-1.
inline void stir_by_id(Grains& g, std::uint64_t seed, double max_speed = 0.3, double max_spin = 100.0) {
  std::vector<std::size_t> row(g.n);
  for (std::size_t r = 0; r < g.n; ++r) row[static_cast<std::size_t>(g.pid.id[r])] = r;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-max_speed, max_speed), w(-max_spin, max_spin);
  for (std::size_t id = 0; id < g.n; ++id) {
    const std::size_t r = row[id];
    g.vel.x[r] = u(rng);
    g.vel.y[r] = u(rng);
    g.vel.z[r] = u(rng);
    const double wx = w(rng), wy = w(rng), wz = w(rng);  // drawn either way: the same velocities
    if (!g.spin) continue;
    g.omega.x[r] = wx;
    g.omega.y[r] = wy;
    g.omega.z[r] = wz;
  }
}

// "key=value" for a scene override, the value written with 17 significant digits so it reads back exactly.
// Position, velocity and angular velocity of every grain, indexed by id, as raw bits: bit
// identity is the claim, and comparing bits also tells -0.0 from 0.0 and compares NaNs.
using State = std::vector<std::array<std::uint64_t, 9>>;

inline State state_by_id(const Grains& g) {
  State s(g.n);
  for (std::size_t r = 0; r < g.n; ++r) {
    const double v[9] = {g.pos.x[r], g.pos.y[r], g.pos.z[r], g.vel.x[r], g.vel.y[r],
                         g.vel.z[r], g.omega.x[r], g.omega.y[r], g.omega.z[r]};
    auto& out = s[static_cast<std::size_t>(g.pid.id[r])];
    for (int c = 0; c < 9; ++c) out[c] = std::bit_cast<std::uint64_t>(v[c]);
  }
  return s;
}

// The first point of a 0.5 mm lattice in the box [lo, hi], scanned from the top (largest y) down,
// whose distance to every grain's surface is more than `clearance` plus r: room to insert a grain
// of radius r that touches nothing. Throws when there is none.
inline V3<double> free_spot(const Grains& g, const V3<double>& lo, const V3<double>& hi, double r, double clearance) {
  const double h = 0.5e-3;
  for (double y = hi.y; y >= lo.y; y -= h)
    for (double x = lo.x; x <= hi.x; x += h)
      for (double z = lo.z; z <= hi.z; z += h) {
        bool free = true;
        for (std::size_t i = 0; i < g.n && free; ++i) {
          const double dx = g.pos.x[i] - x, dy = g.pos.y[i] - y, dz = g.pos.z[i] - z;
          const double reach = g.radius.r[i] + r + clearance;
          free = dx * dx + dy * dy + dz * dz > reach * reach;
        }
        if (free) return {x, y, z};
      }
  throw std::runtime_error("free_spot: no room in the box");
}

// A grain of species `type` at rest at p, ready for Grains::queue_insert (solid sphere).
inline GrainRow grain_at(const V3<double>& p, double diameter, double density, std::int32_t type) {
  GrainRow row;
  row.x[0] = p.x, row.x[1] = p.y, row.x[2] = p.z;
  row.radius = 0.5 * diameter;
  row.mass = density * std::numbers::pi / 6.0 * diameter * diameter * diameter;
  row.inv_inertia = 1.0 / (0.4 * row.mass * row.radius * row.radius);
  row.type = type;
  return row;
}

inline std::string set_override(const std::string& key, double value) {
  std::ostringstream os;
  os.precision(17);
  os << key << "=" << value;
  return os.str();
}

inline double norm(const V3<double>& a) { return std::sqrt(dot(a, a)); }

// Contact time of the linear spring-dashpot (normal force not clipped at zero), half a damped period:
// t_c = sqrt(m/k) sqrt(pi^2 + ln^2 e), for the effective mass m, stiffness k and restitution e.
inline double contact_time(double m, double k, double e) {
  const double l = std::log(e);
  return std::sqrt(m / k) * std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

// A binary pack (1 and 3 mm glass, seed-000 contact parameters) placed at random in a closed
// 20 x 30 x 20 mm box: the state the SIMD-against-scalar driver tests stir and compare on. Strong
// gravity (m/s^2, along -y) packs it within a couple of thousand steps; under 500 m/s^2 the soft
// seed-000 springs let a grain on the floor sink past 0.1 of its diameter, so the overlap limit is
// raised to 0.5 (these tests compare drivers, not the physics of the pile).
inline std::string binary_box_scene(int small, int large, double gravity = 9.81) {
  std::ostringstream s;
  s << "[run]\ndt = 1.0e-5\nduration = 0.01\nskin = 1.5e-4\nmax_overlap = 0.5\ngravity = [0.0, " << -gravity << ", 0.0]\n"
    << "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
    << "[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
    << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
    << "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.02, 0.03, 0.02]\n"
    << "[[fill]]\nkind = \"random\"\n"
    << "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.02, 0.03, 0.02] }\n"
    << "count = { small = " << small << ", large = " << large << " }\n";
  return s.str();
}

// A scene of this file with Hertz-Mindlin instead of the seed-000 linear law (the [contact] block the
// scenes above write): every species (each has a "density = 2500.0" line) gets a soft material,
// E = 1 MPa and nu = 0.25, that passes the Rayleigh-time check at dt = 1e-5 s; e = 0.5, mu = 0.3,
// mu_r = 0.05.
inline std::string with_hertz_mindlin(std::string scene) {
  const std::string lsd = "model = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
                          "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n";
  const std::size_t at = scene.find(lsd);
  if (at == std::string::npos) throw std::logic_error("with_hertz_mindlin: the scene has no seed-000 [contact] block");
  scene.replace(at, lsd.size(),
                "model = \"hertz_mindlin\"\nrestitution = 0.5\nfriction = 0.3\nrolling_friction = 0.05\n");
  const std::string density = "density = 2500.0\n";
  for (std::size_t d = scene.find(density); d != std::string::npos; d = scene.find(density, d + 1))
    scene.insert(d + density.size(), "youngs_modulus = 1.0e6\npoisson_ratio = 0.25\n");
  return scene;
}

// A small rotating drum (24 mm across, 6 mm deep, 3 rad/s about z) of 400 grains of 1 mm and 20 of
// 3 mm with seed 000's contact parameters (Table 4), poured at random: the scene the checkpoint and
// stability tests run. `extra_run` is appended to [run] (e.g. "max_overlap = 0.3\n"); a positive
// settle_time adds a [settle] stage.
inline std::string small_drum_scene(double gravity, const std::string& extra_run = "", double settle_time = 0.0) {
  std::ostringstream s;
  s.precision(17);
  s << "[run]\ndt = 1.0e-5\nduration = 0.02\nskin = 1.5e-4\ngravity = [0.0, " << -gravity << ", 0.0]\nseed = 7\n"
    << extra_run
    << "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
    << "[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
    << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
    << "[[wall]]\ntype = \"drum\"\ncenter = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = 0.012\n"
    << "length = 0.006\nomega = 3.0\n"
    << "[[fill]]\nkind = \"random\"\n"
    << "region = { shape = \"cylinder\", center = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0], radius = 0.012, "
    << "length = 0.006 }\ncount = { small = 400, large = 20 }\n";
  if (settle_time > 0) s << "[settle]\ntime = " << settle_time << "\n";
  s << "[output]\nseries_interval = 1.0e-3\nframe_interval = 2.0e-3\n";
  return s.str();
}

// A 3 cm tank of liquid with a free surface, three 2 mm grains inside, 16 DEM sub-steps per step.
inline std::string coupled_tank_scene(const std::string& coupling = "substeps = 16\nsmoothing_radius = 0.0075\n",
                               const std::string& extra = "") {
  return "[run]\ndt = 5.0e-4\nduration = 0.01\ngravity = [0.0, -9.81, 0.0]\nskin = 2.0e-4\n"
         "[liquid]\ndim = 3\nl0 = 0.003\ndensity = 1000.0\nviscosity = 1.0e-5\n"
         "[geometry]\ntype = \"tank\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.04, 0.03]\n"
         "[[fluid]]\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.03, 0.03]\n"
         "[[species]]\nname = \"glass\"\ndiameter = 2.0e-3\ndensity = 2500.0\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
         "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
         "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.04, 0.03]\n"
         "[[fill]]\nkind = \"random\"\n"
         "region = { shape = \"box\", lo = [0.01, 0.01, 0.01], hi = [0.02, 0.02, 0.02] }\ncount = { glass = 3 }\n"
         "[coupling]\n" + coupling + extra;
}

// Starts the grainflow binary with `args` (argv[1] on) in the background, stdout and stderr to the
// file `log`, and returns its pid (-1 if fork failed). Everything the child needs is prepared
// before fork; after it, only async-signal-safe calls.
inline pid_t spawn_cli(const std::vector<std::string>& args, const std::string& log) {
  const std::string bin = GRAINFLOW_BINARY;
  std::vector<const char*> argv{bin.c_str()};
  for (const std::string& a : args) argv.push_back(a.c_str());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      ::dup2(fd, 1);
      ::dup2(fd, 2);
    }
    ::execv(bin.c_str(), const_cast<char* const*>(argv.data()));
    ::_exit(127);
  }
  return pid;
}

// The grainflow binary run with `args` (shell words, quoted by the caller), stdout and stderr captured
// in files of `dir`.
struct Exit {
  bool exited = false;  // false: killed by a signal (a crash)
  int code = -1;
  std::string out, err;
};

std::string quote(const std::string& s) { return "'" + s + "'"; }

Exit run_cli(const TempDir& dir, const std::string& args) {
  const std::filesystem::path out = dir.path / "stdout.txt", err = dir.path / "stderr.txt";
  const std::string cmd = quote(GRAINFLOW_BINARY) + " " + args + " > " + quote(out.string()) + " 2> " +
                          quote(err.string()) + " < /dev/null";
  const int status = std::system(cmd.c_str());
  Exit e;
  // std::system runs sh -c; a child killed by a signal shows as exit code 128 + signal there.
  e.exited = status != -1 && WIFEXITED(status) && WEXITSTATUS(status) < 128;
  e.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  e.out = read_file(out);
  e.err = read_file(err);
  return e;
}

}  // namespace gf::test
