// Spheres among composite grains: [[shape]] kind = "sphere" (a point member dilated by its radius,
// with exact mass properties) and kind = "spheres" (a clump, its mass properties counted on the
// voxel grid), stepped with the bodies. A sphere rests on a fixed box at the spring's static overlap,
// rebounds from a wall with the law's restitution, and a sphere meeting a box head-on conserves the
// pair's momentum; a clump of two overlapping spheres has the volume of their union.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "engine/scene.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/body_test_support.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

// No rolling spring (a point member's rolling lever is its radius, which these cases do not exercise).
std::string scene(const std::string& run, const std::string& rest) { return gf::test::body_scene(run, rest); }

const std::string kBall =
    "[[shape]]\nname = \"ball\"\nkind = \"sphere\"\nradius = 0.005\ndensity = 2500.0\n\n";

std::string load_error(const std::string& text) {
  return gf::test::scene_error_of([&] { gf::DemSimulation::from_text(text); });
}

}  // namespace

TEST_CASE("a sphere shape has the exact mass and moments of a sphere") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(
      scene("duration = 0.0\ngravity = [0.0, 0.0, 0.0]\n", kBall + "[[bodies]]\nshape = \"ball\"\npositions = [[0, 0, 0]]\n"));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 1);
  const double m = 2500.0 * 4.0 / 3.0 * kPi * 0.005 * 0.005 * 0.005;
  // Closed forms, computed the same way: equal to the last bits.
  CHECK(b.mass.m[0] == Approx(m).epsilon(1e-14));
  for (double i : {b.inertia.i1[0], b.inertia.i2[0], b.inertia.i3[0]}) CHECK(i == Approx(0.4 * m * 25e-6).epsilon(1e-14));
}

TEST_CASE("a clump of two overlapping spheres has the volume of their union") {
  // Two spheres of r = 5 mm, centres 6 mm apart: the union is two spheres less the lens they share,
  // pi (4 r + d)(2 r - d)^2 / 12. The voxel edge 0.25 mm (r / 20) counts the union within 1 %
  // (mass_properties_test.cpp measures the grid's error on single shapes at this resolution).
  const std::string clump = "[[shape]]\nname = \"pair\"\nkind = \"spheres\"\ncentres = [[-0.003, 0, 0], [0.003, 0, 0]]\n"
                            "radius = 0.005\ndensity = 1000.0\ngrid = 2.5e-4\n\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(
      scene("duration = 0.0\ngravity = [0.0, 0.0, 0.0]\n", clump + "[[bodies]]\nshape = \"pair\"\npositions = [[0, 0, 0]]\n"));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const double r = 0.005, d = 0.006;
  const double lens = kPi * (4 * r + d) * (2 * r - d) * (2 * r - d) / 12.0;
  const double volume = 2.0 * 4.0 / 3.0 * kPi * r * r * r - lens;
  INFO("mass " << b.mass.m[0] << " kg, union " << 1000.0 * volume << " kg");
  CHECK(b.mass.m[0] == Approx(1000.0 * volume).epsilon(0.01));
  REQUIRE(sim.world().tables.get<gf::Members>().n == 2);
}

TEST_CASE("a sphere on a fixed box rests at the box's top plus its radius less m g / kn") {
  const std::string rest = kBall +
                           "[[shape]]\nname = \"slab\"\nkind = \"box\"\nsize = [0.1, 0.02, 0.1]\nradius = 0.002\n"
                           "density = 2500.0\ngrid = 2.0e-3\n\n"
                           "[[bodies]]\nshape = \"slab\"\nfixed = true\npositions = [[0.0, -0.01, 0.0]]\n\n"
                           "[[bodies]]\nshape = \"ball\"\npositions = [[0.003, 0.01, 0.0]]\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene("duration = 0.3\ngravity = [0.0, -9.81, 0.0]\n", rest));
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 2);
  // The slab's top face is at y = 0; the fixed slab is a wall for the law (m* = the sphere's mass).
  // A point member on a face touches at one point straight below its centre: it neither rocks nor
  // creeps, so after 0.3 s (about 40 damping times of the contact) it sits at the static overlap to
  // the integration's round-off.
  const double expected = 0.005 - b.mass.m[1] * 9.81 / 1.0e4;
  INFO("y = " << b.pos.y[1] << " m, expected " << expected << " m, off by " << b.pos.y[1] - expected << " m");
  CHECK(std::abs(b.pos.y[1] - expected) < 1.0e-9);
  CHECK(std::abs(b.vel.y[1]) < 1.0e-6);
  CHECK(std::abs(b.pos.x[1] - 0.003) < 1.0e-9);
}

TEST_CASE("a sphere rebounds from a plane wall with the law's restitution") {
  // Head-on at 0.5 m/s, no gravity: the linear spring-dashpot's rebound over impact speed is en for
  // a contact that ends when the overlap returns to zero. The contact lasts pi / sqrt(kn / m) (about
  // 1.1 ms, 110 steps), so the stepping's error on it is well under 1e-3.
  const std::string rest = kBall +
                           "[[wall]]\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n\n"
                           "[[bodies]]\nshape = \"ball\"\npositions = [[0.0, 0.006, 0.0]]\nvelocity = [0.0, -0.5, 0.0]\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene("duration = 0.02\ngravity = [0.0, 0.0, 0.0]\n", rest));
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  INFO("rebound " << b.vel.y[0] << " m/s");
  CHECK(b.vel.y[0] / 0.5 == Approx(0.5).margin(1.0e-3));
  CHECK(b.pos.y[0] > 0.006);
}

TEST_CASE("a sphere meeting a moving box head-on conserves the pair's momentum") {
  const std::string rest = kBall +
                           "[[shape]]\nname = \"cube\"\nkind = \"box\"\nsize = [0.02, 0.02, 0.02]\nradius = 0.002\n"
                           "density = 2500.0\ngrid = 5.0e-4\n\n"
                           "[[bodies]]\nshape = \"cube\"\npositions = [[0.0, 0.0, 0.0]]\n\n"
                           "[[bodies]]\nshape = \"ball\"\npositions = [[0.0, 0.0175, 0.0]]\nvelocity = [0.0, -0.5, 0.0]\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene("duration = 0.02\ngravity = [0.0, 0.0, 0.0]\n", rest));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const double p0 = b.mass.m[1] * -0.5;
  sim.advance(sim.scene().main_steps());
  const double p = b.mass.m[0] * b.vel.y[0] + b.mass.m[1] * b.vel.y[1];
  INFO("momentum before " << p0 << ", after " << p << " kg m/s; box " << b.vel.y[0] << ", ball " << b.vel.y[1] << " m/s");
  // Equal and opposite contact forces: conserved to round-off.
  CHECK(std::abs(p - p0) < 1.0e-12 * std::abs(p0));
  CHECK(b.vel.y[0] < 0.0);             // the box was pushed
  CHECK(b.vel.y[1] > b.vel.y[0]);      // and they have parted
}

TEST_CASE("sphere shapes refuse a zero radius, an empty clump and a grid, naming the key") {
  const std::string base = "duration = 0.0\ngravity = [0.0, 0.0, 0.0]\n";
  const std::string bodies = "[[bodies]]\nshape = \"ball\"\npositions = [[0, 0, 0]]\n";
  CHECK_THAT(load_error(scene(base, "[[shape]]\nname = \"ball\"\nkind = \"sphere\"\nradius = 0.0\ndensity = 2500.0\n\n" + bodies)),
             Catch::Contains("shape[0].radius"));
  CHECK_THAT(load_error(scene(base, kBall.substr(0, kBall.size() - 1) + "grid = 1.0e-4\n\n" + bodies)),
             Catch::Contains("shape[0].grid"));
  CHECK_THAT(load_error(scene(base, "[[shape]]\nname = \"ball\"\nkind = \"spheres\"\nradius = 0.005\ndensity = 2500.0\n\n" + bodies)),
             Catch::Contains("shape[0].centres"));
}
