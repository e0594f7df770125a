// Lift on a grain (systems/coupling/lift.hpp): Mei's factor at hand-computed points and its Saffman limit;
// the shear lift's size and direction in a simple shear; the spin lift's Rubinow-Keller limit and Magnus's
// direction; both zero without slip; and in a coupled tank with both lifts on, the liquid takes back the grains'
// whole impulse, lift included.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <algorithm>

#include "systems/coupling/coupled_step.hpp"
#include "systems/coupling/lift.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

const gf::LiquidProps kWater{1000.0, 1e-3};
double norm(const gf::V3<double>& a) { return std::sqrt(gf::dot(a, a)); }

}  // namespace

TEST_CASE("Mei's lift factor at hand-computed points, and Saffman's limit at small Reynolds numbers") {
  // Re_p 10, Re_s 5: beta 0.25, f = (1 - 0.3314 * 0.5) e^-1 + 0.3314 * 0.5.
  CHECK(gf::mei_lift_factor(10.0, 5.0) == Approx((1.0 - 0.1657) * std::exp(-1.0) + 0.1657).epsilon(1e-12));
  // Above Re_p 40: 0.0524 sqrt(beta Re_p) = 0.0524 * 5 at Re_p 100, beta 0.25.
  CHECK(gf::mei_lift_factor(100.0, 50.0) == Approx(0.262).epsilon(1e-12));
  // Re_p -> 0: f -> 1, Saffman's own force.
  CHECK(gf::mei_lift_factor(1e-9, 1e-9) == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("shear lift: a grain lagging the liquid in a shear is pushed towards the faster liquid, by Saffman-Mei") {
  // u = (G y, 0, 0): the vorticity is (0, 0, -G). The grain lags by s along x.
  const double G = 20.0, s = 0.05, d = 2e-3;
  const gf::V3<double> F = gf::shear_lift({s, 0.0, 0.0}, {0.0, 0.0, -G}, d, kWater);
  const double re_p = 1000.0 * d * s / 1e-3, re_s = 1000.0 * d * d * G / 1e-3;
  const double expected = 1.615 * d * d * std::sqrt(1000.0 * 1e-3 / G) * gf::mei_lift_factor(re_p, re_s) * s * G;
  CHECK(F.y > 0.0);  // towards +y, where the liquid is faster
  CHECK(F.y == Approx(expected).epsilon(1e-12));
  CHECK(F.x == 0.0);
  CHECK(F.z == 0.0);
  // A grain leading the liquid is pushed the other way; no slip or no shear, no lift.
  CHECK(gf::shear_lift({-s, 0.0, 0.0}, {0.0, 0.0, -G}, d, kWater).y == Approx(-expected).epsilon(1e-12));
  CHECK(norm(gf::shear_lift({0.0, 0.0, 0.0}, {0.0, 0.0, -G}, d, kWater)) == 0.0);
  CHECK(norm(gf::shear_lift({s, 0.0, 0.0}, {0.0, 0.0, 0.0}, d, kWater)) == 0.0);
}

TEST_CASE("spin lift: Rubinow and Keller's force at small Reynolds numbers, Magnus's direction") {
  // A grain moving along +x at V through still liquid, spinning at w about +z: slip (-V, 0, 0), the liquid's
  // relative spin (0, 0, -w); the Magnus force points to +y.
  const double V = 1e-4, w = 0.05, d = 1e-3;
  const gf::V3<double> F = gf::spin_lift({-V, 0.0, 0.0}, {0.0, 0.0, -w}, d, kWater);
  // Re_p 1e-4, Re_r 5e-5: C differs from Re_r / Re_p by the exponential's 0.057 Re_r^0.4 Re_p^0.3, about 1e-4
  // of it, so the force is Rubinow and Keller's (pi / 8) rho d^3 w V to 1e-3.
  CHECK(F.y > 0.0);
  CHECK(F.y == Approx(std::numbers::pi / 8.0 * 1000.0 * d * d * d * w * V).epsilon(1e-3));
  CHECK(F.x == 0.0);
  // At a finite Reynolds number the coefficient at hand: Re_p 100, Re_r 10.
  const double C = 0.45 + (0.1 - 0.45) * std::exp(-0.05684 * std::pow(10.0, 0.4) * std::pow(100.0, 0.3));
  CHECK(gf::spin_lift_coefficient(100.0, 10.0) == Approx(C).epsilon(1e-12));
  CHECK(norm(gf::spin_lift({0.0, 0.0, 0.0}, {0.0, 0.0, -w}, d, kWater)) == 0.0);
  CHECK(norm(gf::spin_lift({-V, 0.0, 0.0}, {0.0, 0.0, 0.0}, d, kWater)) == 0.0);
}

TEST_CASE("with both lifts on, the liquid takes back the grains' whole impulse, and the lift acts", "[coupled]") {
  // The shared tank of three grains, the liquid stirred into a shear along x so that the grains lag it in a
  // vorticity and spin.
  const std::string coupling = "substeps = 16\nsmoothing_radius = 0.0075\n";
  auto run = [&](const std::string& lift) {
    gf::CoupledSimulation sim = gf::CoupledSimulation::from_text(gf::test::coupled_tank_scene(coupling + lift, ""));
    gf::World& w = sim.world();
    auto& f = w.tables.get<gf::FluidNodes>();
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f.kind[i] == gf::kFluid) f.u[i] = 20.0 * f.y[i];
    for (std::size_t i = 0; i < w.grains.n_owned; ++i) w.grains.omega.z[i] = 30.0;
    sim.prime();
    const auto& c = w.resources.get<gf::CouplingState>();
    double largest_gap = 0;
    for (int step = 0; step < 5; ++step) {
      sim.step_once();
      largest_gap = std::max(largest_gap, norm(c.grain_impulse + c.reaction_impulse) / norm(c.grain_impulse));
    }
    return std::pair{largest_gap, gf::V3<double>{w.grains.vel.x[0], w.grains.vel.y[0], w.grains.vel.z[0]}};
  };
  const auto [gap, v_lift] = run("shear_lift = \"saffman_mei\"\nspin_lift = \"oesterle_bui_dinh\"\n");
  const auto [gap0, v_plain] = run("");
  CAPTURE(gap, v_lift.y, v_plain.y);
  CHECK(gap <= 1e-13);
  CHECK(gap0 <= 1e-13);
  CHECK(v_lift.y != v_plain.y);  // the lift changed the grain's motion across the shear
}
