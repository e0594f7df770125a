// Contacts between grains of a size distribution (systems/contact/size_scaling.hpp): each law's constants
// rescaled from the nominal grains equal those computed from the contact's own grains, and in a scene the
// linear law's restitution is the scene's en for every pair of sizes and against a wall, as it is for
// grains of one size.
//
// Tolerances. Rescaling reorders a product of a few roundings: 1e-13 relative. A free head-on collision
// under the linear spring-dashpot (the normal force not clipped) has restitution exactly en in continuous
// time; in steps, the contact starts and ends between two of them. Measured at dt = 1e-6 s (86 to 620
// steps per contact) the error is 0.6 % for two 1 mm grains and 2.2 % for a 1 mm grain on the wall,
// falling to 0.3 % and 0.5 % at dt = 2.5e-7 s; 3 % bounds it, while constants left at the nominal
// (smallest) grains' would give 0.43 to 0.81 instead of 0.3 (the damping ratio falls with the square
// root of the effective mass).
#include "systems/contact/hertz_mindlin.hpp"
#include "systems/contact/linear_spring_dashpot.hpp"
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "tests/test_support.hpp"

using gf::ContactBody;
using gf::SizeRatio;

namespace {

constexpr double kRho = 2500.0;

template <class Law>
ContactBody<typename Law::Material> sphere(double r, typename Law::Material m = {}) {
  const double mass = kRho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return {mass, 0.4 * mass * r * r, r, m, false};
}

// Law's constants for grains a and b computed directly, against those of the nominal grains a0 and b0 rescaled.
template <class Law>
void check_rescaled(const typename Law::Params& p, typename Law::Material mat) {
  const auto a = sphere<Law>(1.3e-3, mat), b = sphere<Law>(0.6e-3, mat);
  const auto a0 = sphere<Law>(0.5e-3, mat), b0 = sphere<Law>(0.45e-3, mat);
  ContactBody<typename Law::Material> wall;
  wall.wall = true;
  const auto direct = Law::constants(a, b, p);
  auto scaled = Law::constants(a0, b0, p);
  Law::resize(scaled, gf::pair_size_ratio(a.mass, b.mass, a.radius, b.radius, a0.mass, b0.mass, a0.radius, b0.radius));
  for (std::size_t k = 0; k < direct.size(); ++k) CHECK(scaled[k] == Approx(direct[k]).epsilon(1e-13));
  const auto direct_wall = Law::constants(a, wall, p);
  auto scaled_wall = Law::constants(a0, wall, p);
  Law::resize(scaled_wall, gf::wall_size_ratio(a.mass, a.radius, a0.mass, a0.radius));
  for (std::size_t k = 0; k < direct_wall.size(); ++k) CHECK(scaled_wall[k] == Approx(direct_wall[k]).epsilon(1e-13));
}

// Two grains of a discrete species (1, 2 and 3 mm) meeting head-on at 0.1 m/s in free space, or one
// grain against a plane at x = 0: the restitution measured from the velocities after they part.
double restitution(double d_a, double d_b, bool wall) {
  std::string scene =
      "[run]\ndt = 1.0e-6\nduration = 0.01\nskin = 1.0e-4\ngravity = [0.0, 0.0, 0.0]\n"
      "[[species]]\nname = \"glass\"\ndensity = 2500.0\n"
      "diameter = { distribution = \"discrete\", diameters = [1.0e-3, 2.0e-3, 3.0e-3], fractions = [1, 1, 1] }\n"
      "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
      "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
      "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [-0.05, -0.05, -0.05], hi = [0.05, 0.05, 0.05] }\n"
      "count = { glass = 2 }\n";
  if (wall) scene += "[[wall]]\ntype = \"plane\"\npoint = [-0.06, 0.0, 0.0]\nnormal = [1.0, 0.0, 0.0]\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene);
  gf::Grains& g = sim.grains();
  const double d[2] = {d_a, wall ? 1e-3 : d_b};
  for (std::size_t i = 0; i < 2; ++i) {
    const double r = 0.5 * d[i], m = kRho * std::numbers::pi / 6.0 * d[i] * d[i] * d[i];
    g.radius.r[i] = r;
    g.mass.m[i] = m;
    g.mass.inv_m[i] = 1.0 / m;
    g.mass.inv_inertia[i] = 1.0 / (0.4 * m * r * r);
    g.pos.y[i] = g.pos.z[i] = 0.0;
    g.vel.x[i] = g.vel.y[i] = g.vel.z[i] = 0.0;
  }
  // Grain 0 approaches at 0.1 m/s from just out of reach: of grain 1, or (far away) of the wall.
  g.pos.x[0] = wall ? -0.06 + 0.5 * d_a + 1e-5 : 0.0;
  g.pos.x[1] = wall ? 0.04 : 0.5 * (d_a + d_b) + 1e-5;
  g.vel.x[0] = wall ? -0.1 : 0.1;
  sim.advance(2000);
  return wall ? g.vel.x[0] / 0.1 : (g.vel.x[1] - g.vel.x[0]) / 0.1;
}

}  // namespace

TEST_CASE("the linear law's constants rescaled to a contact's grains equal those computed for them") {
  gf::LinearSpringDashpot::Params p;
  p.kn = 1000.0, p.kt = 600.0, p.kr = 1e-5, p.en = 0.3, p.et = 0.4, p.er = 0.5, p.friction = 0.3, p.rolling_friction = 5e-5;
  check_rescaled<gf::LinearSpringDashpot>(p, {});
}

TEST_CASE("Hertz-Mindlin's constants rescaled to a contact's grains equal those computed for them") {
  gf::HertzMindlin::Params p;
  p.restitution = 0.5, p.friction = 0.3, p.rolling_friction = 0.05;
  p.wall.youngs_modulus = 7e10, p.wall.poisson_ratio = 0.3;
  check_rescaled<gf::HertzMindlin>(p, {1e7, 0.25});
}

TEST_CASE("grains of a size distribution collide with the scene's restitution whatever their sizes") {
  for (const auto& [a, b] : {std::pair{1e-3, 1e-3}, std::pair{3e-3, 3e-3}, std::pair{3e-3, 1e-3}, std::pair{2e-3, 3e-3}}) {
    CAPTURE(a, b);
    CHECK(restitution(a, b, false) == Approx(0.3).epsilon(0.03));
  }
  CHECK(restitution(3e-3, 0.0, true) == Approx(0.3).epsilon(0.03));
  CHECK(restitution(1e-3, 0.0, true) == Approx(0.3).epsilon(0.03));
}
