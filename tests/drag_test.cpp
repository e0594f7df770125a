// The liquid's force on a grain (systems/coupling/drag.hpp) against closed forms: a lone grain's
// drag is the standard (1/2) rho C_d A |w| w, Stokes' 3 pi mu d w at small Reynolds number; a grain
// released in still liquid reaches the terminal velocity where drag and buoyancy balance its weight;
// a fixed bed's drag per volume is Ergun's pressure gradient; the seed's switch at eps = 0.8 jumps,
// the blended form does not.
#include "systems/coupling/drag.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace {

const gf::LiquidProps kWater{1000.0, 1e-3};
constexpr double kPi = std::numbers::pi;

// The speed at which a lone sphere's drag carries its weight less buoyancy, by bisection.
double terminal_speed(double d, double rho_p, double g) {
  const double volume = kPi / 6.0 * d * d * d, net = (rho_p - kWater.density) * volume * g;
  double lo = 0.0, hi = 100.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (gf::drag_per_volume(1.0, mid, d, kWater) * volume * mid < net ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST_CASE("drag: a lone grain feels the standard drag, Stokes' law at small Reynolds number", "[drag]") {
  const double d = 1e-3;
  for (const double re : {0.1, 10.0, 500.0, 2000.0}) {
    const double w = re * kWater.viscosity / (kWater.density * d);
    const gf::V3<double> f = gf::drag_force({0, 0, w}, {0, 0, 0}, 1.0, d, kWater);
    const double standard = 0.5 * kWater.density * gf::schiller_naumann(re) * (kPi / 4.0 * d * d) * w * w;
    INFO("Re " << re);
    CHECK(f.z == Approx(standard).epsilon(1e-12));
    CHECK(f.x == 0.0);
  }
  // Re = 1e-4: Schiller-Naumann's correction 0.15 Re^0.687 is 2.7e-4 of Stokes' drag.
  const double w = 1e-4 * kWater.viscosity / (kWater.density * d);
  const gf::V3<double> f = gf::drag_force({w, 0, 0}, {0, 0, 0}, 1.0, d, kWater);
  CHECK(f.x == Approx(3.0 * kPi * kWater.viscosity * d * w).epsilon(3e-4));
  // At zero slip the coefficient is the Stokes limit, and the force zero.
  CHECK(gf::drag_per_volume(1.0, 0.0, d, kWater) == Approx(18.0 * kWater.viscosity / (d * d)).epsilon(1e-12));
}

TEST_CASE("drag: a grain released in still liquid reaches its terminal velocity", "[drag]") {
  // 1 mm glass in water (Re about 150 at the end) and 0.1 mm (Re about 0.7): m dv/dt = m g + F_int
  // with the liquid at rest, by RK4 with a step of a hundredth of the relaxation time d^2 rho_p /
  // (18 mu), for forty relaxation times. The speed approaches the balance of weight, buoyancy and
  // drag found by bisection; the gap left after forty relaxation times is below 1e-9 of it.
  const gf::V3<double> g{0.0, -9.81, 0.0};
  for (const double d : {1e-3, 1e-4}) {
    const double rho_p = 2500.0, m = rho_p * kPi / 6.0 * d * d * d;
    const double tau = d * d * rho_p / (18.0 * kWater.viscosity), h = tau / 100.0;
    auto accel = [&](double vy) {
      return g.y + gf::liquid_force({0, 0, 0}, {0, vy, 0}, 1.0, d, kWater, g).y / m;
    };
    double vy = 0.0;
    for (int k = 0; k < 4000; ++k) {
      const double k1 = accel(vy), k2 = accel(vy + 0.5 * h * k1), k3 = accel(vy + 0.5 * h * k2), k4 = accel(vy + h * k3);
      vy += h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    const double vt = terminal_speed(d, rho_p, 9.81);
    INFO("d " << d << ": terminal " << vt << " m/s, Re " << kWater.density * d * vt / kWater.viscosity);
    CHECK(-vy == Approx(vt).epsilon(1e-9));
  }
}

TEST_CASE("drag: a fixed bed's drag per volume is Ergun's pressure gradient", "[drag]") {
  // Grains of volume V_p at liquid fraction eps: (1 - eps) / V_p of them per volume, each feeling
  // F_d / eps at the interstitial slip U / eps (U the superficial velocity). Their sum per volume is
  // 150 mu (1 - eps)^2 U / (eps^3 d^2) + 1.75 rho (1 - eps) U^2 / (eps^3 d), Ergun's gradient, by algebra.
  const double d = 2e-3, vp = kPi / 6.0 * d * d * d;
  for (const double eps : {0.36, 0.45, 0.6, 0.8})
    for (const double u : {1e-4, 1e-2, 0.3}) {
      const gf::V3<double> f = gf::drag_force({0, u / eps, 0}, {0, 0, 0}, eps, d, kWater);
      const double per_volume = (1.0 - eps) / vp * f.y / eps;
      const double ergun = 150.0 * kWater.viscosity * (1 - eps) * (1 - eps) * u / (eps * eps * eps * d * d) +
                           1.75 * kWater.density * (1 - eps) * u * u / (eps * eps * eps * d);
      INFO("eps " << eps << ", U " << u);
      CHECK(per_volume == Approx(ergun).epsilon(1e-12));
    }
}

TEST_CASE("drag: the seed's switch at eps = 0.8 jumps, the blended form does not", "[drag]") {
  const double d = 2e-3;
  const double slow = gf::drag_switch_jump(1e-3, d, kWater), fast = gf::drag_switch_jump(1.0, d, kWater);
  CHECK(slow == Approx(0.957).margin(0.001));
  CHECK(fast == Approx(0.27).margin(0.005));
  for (const double slip : {1e-3, 0.05, 1.0}) {
    const double jump = gf::drag_switch_jump(slip, d, kWater);
    const double below = gf::drag_per_volume(0.8, slip, d, kWater), above = gf::drag_per_volume(0.8 + 1e-12, slip, d, kWater);
    INFO("slip " << slip << " m/s: Wen-Yu / Ergun at 0.8 = " << jump);
    CHECK(above / below == Approx(jump).epsilon(1e-9));
    // Wen-Yu lies below Ergun there: by 4 % at 1 mm/s (both near their viscous limits, 18 mu
    // 0.8^-2.65 / d^2 against 150 x 0.2 / 0.8 mu / d^2, then the Re corrections), by a factor of 3.7
    // at 1 m/s (Re = 1600, C_d = 0.44 against Ergun's inertial term): why a blended form is offered.
    CHECK(jump < 1.0);
    const double b0 = gf::drag_per_volume(0.8 - 1e-9, slip, d, kWater, gf::drag_law("blend"));
    const double b1 = gf::drag_per_volume(0.8 + 1e-9, slip, d, kWater, gf::drag_law("blend"));
    CHECK(b1 / b0 == Approx(1.0).epsilon(1e-6));
    // Far from the switch the blend is its nearer form to within the blend's tail, atan(262.5 x 0.2) / pi.
    const double dense = gf::drag_per_volume(0.4, slip, d, kWater, gf::drag_law("blend"));
    CHECK(dense == Approx(gf::drag_per_volume(0.4, slip, d, kWater)).epsilon(0.05));
  }
}

TEST_CASE("drag: out-of-range arguments are refused", "[drag]") {
  CHECK_THROWS_AS(gf::drag_per_volume(0.0, 1.0, 1e-3, kWater), std::invalid_argument);
  CHECK_THROWS_AS(gf::drag_per_volume(1.2, 1.0, 1e-3, kWater), std::invalid_argument);
  CHECK_THROWS_AS(gf::drag_per_volume(0.5, -1.0, 1e-3, kWater), std::invalid_argument);
  CHECK_THROWS_AS(gf::drag_per_volume(0.5, 1.0, 0.0, kWater), std::invalid_argument);
  CHECK_THROWS_AS(gf::drag_per_volume(0.5, 1.0, 1e-3, gf::LiquidProps{1000.0, 0.0}), std::invalid_argument);
  CHECK_THROWS_AS(gf::schiller_naumann(0.0), std::invalid_argument);
}

TEST_CASE("drag: the registry names its laws and refuses an unknown one", "[drag]") {
  CHECK(gf::drag_law_names() == std::vector<std::string>{"ergun_wen_yu", "blend"});
  CHECK(&gf::drag_law("ergun_wen_yu") == &gf::drag_laws()[0]);  // the default first
  for (const gf::DragLaw& law : gf::drag_laws()) {
    CHECK_FALSE(law.meaning.empty());
    // Each law through the registry is its function: the same number as calling it.
    CHECK(gf::drag_per_volume(0.5, 0.1, 2e-3, kWater, law) == law.per_volume(0.5, 0.1, 2e-3, kWater));
  }
  CHECK_THROWS_WITH(gf::drag_law("stokes"), Catch::Matchers::Contains("no drag law is named 'stokes'") &&
                                                Catch::Matchers::Contains("'ergun_wen_yu', 'blend'"));
}
