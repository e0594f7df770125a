// Composite grains from a scene file: a box body dropped on a plane wall comes to rest at its
// half-height less the spring's static overlap, stepped by the DEM step the scene builds; malformed
// [[shape]] and [[bodies]] tables and scenes mixing bodies with what they cannot meet yet are refused
// naming the key.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "engine/scene.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

// A 20 mm box (rounded by 2 mm) of 2500 kg/m^3 released 30 mm above a floor at y = 0.
const std::string kScene = R"(
[run]
dt = 1.0e-5
duration = 0.4
skin = 1.0e-3
gravity = [0.0, -9.81, 0.0]

[contact]
model = "linear_spring_dashpot"
kn = 1.0e4
kt = 6.0e3
kr = 1.0e-3
en = 0.3
et = 0.3
er = 0.3
friction = 0.5
rolling_friction = 0.0

[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]

[[shape]]
name = "cube"
kind = "box"
size = [0.02, 0.02, 0.02]
radius = 0.002
density = 2500.0
grid = 5.0e-4

[[bodies]]
shape = "cube"
positions = [[0.0, 0.04, 0.0]]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string load_error(const std::string& text) {
  try {
    gf::DemSimulation::from_text(text);
  } catch (const gf::SceneError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a box body dropped on a plane wall rests at its half-height less m g / kn") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(kScene);
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 1);
  // One member, one plane contact: the static overlap is m g / kn with the body's voxel mass.
  const double expected = 0.01 - b.mass.m[0] * 9.81 / 1.0e4;
  INFO("y = " << b.pos.y[0] << " m, expected " << expected << " m, off by " << b.pos.y[0] - expected << " m");
  CHECK(std::abs(b.pos.y[0] - expected) < 1.0e-7);
  CHECK(std::abs(b.vel.y[0]) < 1.0e-4);
  CHECK(std::abs(b.pos.x[0]) < 1.0e-9);
  // A face lands flat: no spin left (the cube's principal axes, and so q, are arbitrary).
  CHECK(std::hypot(b.omega.x[0], b.omega.y[0], b.omega.z[0]) < 1.0e-6);
}

TEST_CASE("malformed shape and bodies keys are refused naming the key") {
  CHECK_THAT(load_error(replaced(kScene, "kind = \"box\"", "kind = \"ball\"")), Catch::Contains("shape[0].kind"));
  CHECK_THAT(load_error(replaced(kScene, "size = [0.02, 0.02, 0.02]", "size = [0.02, 0.02]")),
             Catch::Contains("shape[0].size"));
  CHECK_THAT(load_error(replaced(kScene, "radius = 0.002", "radius = 0.02")), Catch::Contains("shape[0].kind"));
  CHECK_THAT(load_error(replaced(kScene, "shape = \"cube\"", "shape = \"cubes\"")), Catch::Contains("bodies[0].shape"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, 0.04]]")),
             Catch::Contains("bodies[0].positions"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, -0.04, 0.0]]")),
             Catch::Contains("behind wall"));
  CHECK_THAT(load_error(kScene + "\n[[fill]]\nkind = \"random\"\n"), Catch::Contains("fill"));
  CHECK_THAT(load_error(replaced(kScene, "type = \"plane\"", "type = \"cylinder\"")), Catch::Contains("wall[0].type"));
}

TEST_CASE("bodies placed by count in a region keep their bounding spheres apart") {
  const std::string text = replaced(kScene, "positions = [[0.0, 0.04, 0.0]]",
                                    "count = 6\norientation = \"random\"\n"
                                    "region = { shape = \"box\", lo = [-0.05, 0.02, -0.05], hi = [0.05, 0.1, 0.05] }");
  gf::DemSimulation sim = gf::DemSimulation::from_text(text);
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 6);
  const double bound = std::sqrt(3.0) * 0.008 + 0.002;  // the core's corner distance + r
  for (std::size_t i = 0; i < b.n; ++i)
    for (std::size_t j = i + 1; j < b.n; ++j)
      CHECK(std::hypot(b.pos.x[i] - b.pos.x[j], b.pos.y[i] - b.pos.y[j], b.pos.z[i] - b.pos.z[j]) >= 2 * bound);
  sim.advance(100);
}

TEST_CASE("body scene: grainflow check and run refuse bodies alike, naming the table and the fix", "[bodies][cli]") {
  gf::test::TempDir dir("body_scene_cli");
  const auto scene = dir.write("bodies.toml", kScene);
  for (const char* command : {"check", "run"}) {
    const std::string out = (dir.path / "out").string();
    const gf::test::Exit e = gf::test::run_cli(
        dir, std::string(command) + " " + gf::test::quote(scene.string()) +
                 (std::string(command) == "run" ? " --out " + gf::test::quote(out) : std::string()));
    INFO(command << ": " << e.err);
    CHECK(e.exited);
    CHECK(e.code != 0);
    CHECK_THAT(e.err, Catch::Matchers::Contains("[[bodies]]") && Catch::Matchers::Contains("Fix:"));
  }
}
