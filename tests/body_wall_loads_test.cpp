// Walls among composite grains (systems/bodies/body_contact.hpp): what a plane wall receives from the
// bodies (its force, its moment about its rotation point and its drive's power, the loads of walls.hpp)
// and walls that translate:
//  - a clump of two spheres at rest on a floor: the floor carries its weight, and the moment of that
//    weight about the floor's point;
//  - a floor sliding under it: friction drags the clump until it moves with the floor, and the drive
//    supplied v * m * dv (the momentum it gave, at its own speed);
//  - a rising floor carries it up at the static overlap;
//  - a wall that would move too far per step is refused, naming its key;
//  - walls.csv of a composite-grain run: seven columns per wall, a row per series row.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/body_test_support.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kG = 9.81;

// Two spheres of r = 5 mm, centres 10 mm apart along x (they touch), 1000 kg/m^3; each rests on its own
// point of the floor, so the clump stands without rocking.
const std::string kClump =
    "[[shape]]\nname = \"pair\"\nkind = \"spheres\"\ncentres = [[-0.005, 0, 0], [0.005, 0, 0]]\n"
    "radius = 0.005\ndensity = 1000.0\ngrid = 5.0e-4\n\n";

// The clump at (x, 5 mm, z) above a floor through the origin (y up), the floor's keys added.
std::string clump_on_floor(double duration, double x, double z, const std::string& floor_keys = "") {
  const std::string rest = kClump + "[[wall]]\ntype = \"plane\"\nname = \"floor\"\npoint = [0.0, 0.0, 0.0]\n"
                                    "normal = [0.0, 1.0, 0.0]\n" + floor_keys + "\n"
                                    "[[bodies]]\nshape = \"pair\"\npositions = [[" + std::to_string(x) +
                           ", 0.005, " + std::to_string(z) + "]]\n";
  return gf::test::body_scene("duration = " + std::to_string(duration) + "\ngravity = [0.0, -9.81, 0.0]\n", rest);
}

// The floor's load on the bodies summed over the steps since `before`, per step.
gf::WallLoad mean_since(const gf::WallLoads& now, const gf::WallLoad& before, std::int64_t steps) {
  const double n = static_cast<double>(steps);
  return {(1.0 / n) * (now.sum[0].force - before.force), (1.0 / n) * (now.sum[0].moment - before.moment),
          (now.sum[0].power - before.power) / n};
}

}  // namespace

TEST_CASE("a clump at rest on a floor: the floor carries its weight and the weight's moment", "[bodies][walls]") {
  const double x = 0.03, z = -0.02;
  gf::DemSimulation sim = gf::DemSimulation::from_text(clump_on_floor(0.4, x, z));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const gf::WallLoads& loads = sim.world().resources.get<gf::BodyContactState>().loads;
  // 0.3 s settle the drop of its static overlap (about 40 damping times of the contact), then 0.1 s.
  sim.advance(30000);
  REQUIRE(loads.sum.size() == 1);
  const gf::WallLoad before = loads.sum[0];
  const std::int64_t from = loads.steps;
  sim.advance(10000);
  const gf::WallLoad mean = mean_since(loads, before, loads.steps - from);
  const double weight = b.mass.m[0] * kG;
  // On the clump (walls.csv reports the negatives): straight up, its weight. At rest to 1e-9 m/s, the
  // momentum the window adds is under 1e-8 of the weight's impulse: 1e-6 is rounding over 1e4 steps.
  INFO("force " << mean.force.x << " " << mean.force.y << " " << mean.force.z << " N, weight " << weight << " N");
  CHECK(mean.force.y == Approx(weight).epsilon(1e-6));
  CHECK(std::abs(mean.force.x) < 1e-6 * weight);
  CHECK(std::abs(mean.force.z) < 1e-6 * weight);
  // About the floor's point (the origin): (c - o) x F = (-z W, 0, x W) for the centre c = (x, y, z).
  INFO("moment " << mean.moment.x << " " << mean.moment.y << " " << mean.moment.z << " N m");
  CHECK(mean.moment.x == Approx(-z * weight).epsilon(1e-5));
  CHECK(mean.moment.z == Approx(x * weight).epsilon(1e-5));
  CHECK(std::abs(mean.moment.y) < 1e-6 * weight * 0.03);
  CHECK(mean.power == 0.0);  // a still floor does no work
}

TEST_CASE("a floor sliding under a clump drags it to its speed and supplies v m dv", "[bodies][walls]") {
  // Friction 0.5 accelerates the clump at mu g = 4.9 m/s^2: it reaches the floor's 0.1 m/s in about
  // 20 ms and then rides with it. The floor's drive does work at its own speed against the friction
  // it applies: sum of P dt = v * sum of F_x dt = v m dv (the normal force is across the motion).
  const double v = 0.1, dt = 1.0e-5;
  gf::DemSimulation sim = gf::DemSimulation::from_text(clump_on_floor(0.15, 0.0, 0.0, "velocity = [0.1, 0.0, 0.0]\n"));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const gf::WallLoads& loads = sim.world().resources.get<gf::BodyContactState>().loads;
  const double v0 = b.vel.x[0];
  sim.advance(sim.scene().main_steps());
  INFO("clump's speed " << b.vel.x[0] << " m/s, floor's " << v << " m/s");
  // Riding with the floor; the rest of a damped stick-slip of the springs is far below 1e-6 m/s.
  CHECK(b.vel.x[0] == Approx(v).epsilon(1e-5));
  const double work = loads.sum[0].power * dt, expected = v * b.mass.m[0] * (b.vel.x[0] - v0);
  INFO("drive's work " << work << " J, v m dv " << expected << " J");
  CHECK(work == Approx(expected).epsilon(1e-9));
  CHECK(work > 0.0);
}

TEST_CASE("a rising floor carries a clump at its static overlap", "[bodies][walls]") {
  // The floor rises at 5 cm/s from the start, under the clump that just touches it: after the jolt
  // (the contact's damping time is about 1 ms) the clump rides with the floor, each sphere's overlap
  // the static m g / (2 kn), so after 0.2 s its centre is at 5 mm + 10 mm less that overlap.
  gf::DemSimulation sim = gf::DemSimulation::from_text(clump_on_floor(0.2, 0.0, 0.0, "velocity = [0.0, 0.05, 0.0]\n"));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  sim.advance(sim.scene().main_steps());
  const double expected = 0.015 - b.mass.m[0] * kG / (2.0 * 1.0e4);
  INFO("y " << b.pos.y[0] << " m, expected " << expected << " m; speed " << b.vel.y[0] << " m/s");
  CHECK(std::abs(b.pos.y[0] - expected) < 1e-9);
  CHECK(b.vel.y[0] == Approx(0.05).epsilon(1e-6));
}

TEST_CASE("a wall translating faster than 0.1 of the thinnest shape per step is refused at its key", "[bodies][walls]") {
  // The clump's thinnest outer dimension is 10 mm: 0.1 of it per step of 1e-5 s is 100 m/s. 150 m/s (a
  // speed typed in mm/s) is refused at `velocity`, naming the shape's scale; 50 m/s is accepted.
  const std::string e = gf::test::scene_error_of(
      [] { gf::DemSimulation::from_text(clump_on_floor(0.01, 0.0, 0.0, "velocity = [150.0, 0.0, 0.0]\n")); });
  INFO(e);
  CHECK(e.find("key 'wall[0].velocity'") != std::string::npos);
  CHECK(e.find("the thinnest moving shape") != std::string::npos);
  CHECK(e.find("mm/s") != std::string::npos);
  CHECK(gf::test::scene_error_of(
            [] { gf::DemSimulation::from_text(clump_on_floor(0.01, 0.0, 0.0, "velocity = [50.0, 0.0, 0.0]\n")); })
            .empty());
}

TEST_CASE("walls.csv of a composite-grain run: a row per series row, seven columns per wall", "[bodies][walls][cli]") {
  const gf::test::TempDir dir("body_walls_csv");
  const std::filesystem::path scene = dir.path / "clump.toml", out = dir.path / "run";
  std::ofstream(scene) << clump_on_floor(0.05, 0.0, 0.0) << "\n[output]\nseries_interval = 0.01\n";
  const gf::test::Exit e = gf::test::run_cli(dir, "run " + gf::test::quote(scene.string()) + " --out " +
                                                       gf::test::quote(out.string()) + " --quiet");
  INFO(e.err);
  REQUIRE(e.code == 0);
  const std::vector<std::string> rows = gf::test::read_lines(out / "walls.csv");
  const std::vector<std::string> series = gf::test::read_lines(out / "series.csv");
  REQUIRE(rows.size() == series.size());
  CHECK(rows[0] == "time,floor.fx,floor.fy,floor.fz,floor.tx,floor.ty,floor.tz,floor.power");
  // The last row, the mean over 40 to 50 ms: the floor pressed down by the clump's weight (its mass as
  // summary.json gives it). The drop's bounce is damped at about 900 /s, so 40 ms after it the clump
  // is at rest to far below 1e-6 of its weight; the csv's shortest round-trip digits lose nothing.
  std::vector<double> last;
  std::stringstream row(rows.back());
  for (std::string cell; std::getline(row, cell, ',');) last.push_back(std::stod(cell));
  REQUIRE(last.size() == 8);
  const double mass = nlohmann::json::parse(gf::test::read_file(out / "summary.json"))["shapes"]["pair"]["mass"];
  CHECK(last[2] == Approx(-mass * kG).epsilon(1e-6));
}
