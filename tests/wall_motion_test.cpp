// Walls that translate (systems/walls/wall_motion.hpp): the offset and velocity of each motion against
// their closed forms, the velocity table's reader and the scene's refusals, and a grain on a vibrating
// floor against the analytic bounce threshold.
//
// The threshold. A floor vibrating vertically, y(t) = A (1 - cos(w t)), pushes a grain resting on it
// with m (g + y''); it loses contact where the floor's downward acceleration passes g, i.e. only if
// Gamma = A w^2 / g > 1. The contact spring adds a dynamic correction of order (w / w_n)^2 to that
// quasi-static force (w_n = sqrt(k / m) = 5320 rad/s for the 3 mm seed-000 grain, w = 126 rad/s at
// 20 Hz: 6e-4), and the step in acceleration at the start rings down within a few contact times
// (damping ratio 0.36 at e = 0.3: e^-10 after 5 ms), so Gamma = 0.97 must keep contact and 1.03 must
// lose it: margins of 3 %, fifty times the correction. The same on a mesh plate. (With the wall's
// velocity taken at the positions' time rather than the half-step's of the grains' velocities, the
// damping would shave 1.9 % off the swing at dt = 1e-5 s: walls.hpp.)
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include "engine/scene.hpp"
#include "systems/walls/wall_motion.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Vec3d;
using gf::WallMotion;
using gf::test::scene_error_of;

namespace {

constexpr double kG = 9.81, kF = 20.0, kR = 1.5e-3;
const double kW = 2.0 * std::numbers::pi * kF;

// One 3 mm seed-000 grain dropped on a floor at y = 0 that settles with the floor still (the [settle]
// stage), after which the floor vibrates at Gamma from rest: phase -pi/2, y = A (1 - cos(w t)).
std::string plate_scene(double gamma, bool mesh) {
  const double a = gamma * kG / (kW * kW);
  std::ostringstream s;
  s.precision(17);
  s << "[run]\ndt = 1.0e-5\nduration = 0.2\nskin = 2.0e-4\ngravity = [0.0, -9.81, 0.0]\n"
    << "[[species]]\nname = \"glass\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
    << "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
    << "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n";
  if (mesh)
    s << "[[wall]]\ntype = \"mesh\"\nprimitive = \"plate\"\ncenter = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n"
      << "axis = [1.0, 0.0, 0.0]\nhalf_widths = [0.01, 0.01]\ncells = [2, 2]\n";
  else
    s << "[[wall]]\ntype = \"plane\"\nname = \"floor\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n";
  s << "vibration_amplitude = [0.0, " << a << ", 0.0]\nvibration_frequency = " << kF
    << "\nvibration_phase = " << -0.5 * std::numbers::pi << "\n"
    << "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [-0.0016, 0.0016, -0.0016], "
    << "hi = [0.0016, 0.0048, 0.0016] }\ncount = { glass = 1 }\n[settle]\ntime = 0.1\n";
  return s.str();
}

// The smallest overlap of the grain with the floor (m; negative: apart) over `periods` periods after
// the first.
double smallest_overlap(double gamma, bool mesh, int periods) {
  DemSimulation sim = DemSimulation::from_text(plate_scene(gamma, mesh));
  sim.settle();
  const double a = gamma * kG / (kW * kW), dt = sim.world().clock.dt;
  const auto steps = static_cast<std::int64_t>(std::llround(1.0 / kF / dt));
  sim.advance(steps);
  double least = INFINITY;
  for (std::int64_t k = 0; k < periods * steps; ++k) {
    sim.advance(1);
    const double t = sim.world().clock.t;
    const double floor = a * (1.0 - std::cos(kW * t));
    least = std::min(least, kR - (sim.grains().pos.y[0] - floor));
  }
  return least;
}

}  // namespace

TEST_CASE("each motion's offset and velocity against its closed form") {
  WallMotion m;
  m.velocity = {0.1, 0.0, -0.2};
  CHECK(m.moves());
  CHECK(m.offset(2.0).x == Approx(0.2));
  CHECK(m.offset(2.0).z == Approx(-0.4));
  CHECK(m.rate(5.0).x == 0.1);

  WallMotion v;
  v.amplitude = {0.0, 1e-3, 0.0};
  v.frequency = 50.0;
  v.phase = 0.3;
  const double w = 2.0 * std::numbers::pi * 50.0;
  for (const double t : {0.0, 0.0013, 0.0101, 0.37}) {
    CHECK(v.offset(t).y == Approx(1e-3 * (std::sin(w * t + 0.3) - std::sin(0.3))).margin(1e-15));
    CHECK(v.rate(t).y == Approx(1e-3 * w * std::cos(w * t + 0.3)).margin(1e-12));
  }
  CHECK(v.fastest() == Approx(1e-3 * w));

  // A ramp from rest to 0.2 m/s over 1 s, then held: the offset is the integral, t^2/10 then 0.1 + 0.2 (t - 1).
  WallMotion r;
  r.set_table({0.0, 1.0}, {Vec3d{0, 0, 0}, Vec3d{0.2, 0, 0}});
  CHECK(r.offset(0.5).x == Approx(0.025));
  CHECK(r.offset(1.0).x == Approx(0.1));
  CHECK(r.offset(3.0).x == Approx(0.5));
  CHECK(r.rate(0.5).x == Approx(0.1));
  CHECK(r.rate(7.0).x == Approx(0.2));
  CHECK(WallMotion{}.moves() == false);
}

TEST_CASE("a velocity table is read with its header and comments, and a bad row is named by its line") {
  const gf::test::TempDir dir("wall_motion");
  const std::filesystem::path good = dir.path / "v.csv", bad = dir.path / "bad.csv";
  std::ofstream(good) << "# a lift\ntime,vx,vy,vz\n0, 0, 0, 0\n0.5, 0, 0.1, 0\n1.0,0,0.1,0\n";
  std::vector<double> t;
  std::vector<Vec3d> v;
  gf::read_velocity_table(good, t, v);
  REQUIRE(t.size() == 3);
  CHECK(v[1].y == 0.1);
  std::ofstream(bad) << "time,vx,vy,vz\n0,0,0,0\n0.5,0,0.1\n";
  std::string msg = scene_error_of([&] { gf::read_velocity_table(bad, t, v); });
  CHECK(msg.find("bad.csv:3") != std::string::npos);
  CHECK(msg.find("3 numbers, not 4") != std::string::npos);
  std::ofstream(bad) << "0,0,0,0\n0.5,0,0.1,0\n0.5,0,0.2,0\n";
  msg = scene_error_of([&] { gf::read_velocity_table(bad, t, v); });
  CHECK(msg.find("bad.csv:3") != std::string::npos);
  CHECK(msg.find("does not follow") != std::string::npos);
  std::ofstream(bad) << "0.1,0,0,0\n";
  CHECK(scene_error_of([&] { gf::read_velocity_table(bad, t, v); }).find("not at 0") != std::string::npos);
}

TEST_CASE("a scene's wall motion is refused where it is incomplete or too fast for the step") {
  const std::string base = plate_scene(1.0, false);
  std::string msg = scene_error_of([&] { DemSimulation::from_text(base, {"wall.0.vibration_frequency=0"}); });
  CHECK(msg.find("vibration_frequency") != std::string::npos);
  CHECK(msg.find("no frequency") != std::string::npos);
  // 2 m/s typed in mm/s: 2000 m/s moves the floor 0.02 m per step, past 0.1 of the 3 mm grain.
  msg = scene_error_of([&] { DemSimulation::from_text(base, {"wall.0.velocity=[0, 2000, 0]"}); });
  CHECK(msg.find("wall[0].velocity") != std::string::npos);
  CHECK(msg.find("mm/s") != std::string::npos);
}

TEST_CASE("a grain on a vibrating floor keeps contact below Gamma = 1 and leaves it above") {
  for (const bool mesh : {false, true}) {
    INFO((mesh ? "mesh plate" : "plane"));
    const double below = smallest_overlap(0.97, mesh, 3), above = smallest_overlap(1.03, mesh, 3);
    // Resting overlap m g / k = 3.47e-7 m; at Gamma = 0.97 the least is 1 - 0.97 (1 + (w/w_n)^2) = 0.0295 of it.
    // 5 %: the spring's phase lag (2 zeta w / w_n = 0.017) shifts the swing's extreme by a fraction of that.
    CHECK(below > 0.0);
    CHECK(below == Approx(0.0295 * 3.4671e-7).epsilon(0.05));
    CHECK(above < 0.0);
  }
}
