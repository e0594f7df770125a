// Hydrostatic tank (scenes/liquid/hydrostatic_2d.toml), short version: the time-averaged floor pressure of a
// still column against rho g H. The full-resolution 2 % check, the 3D tank, the RMS fluctuation and the residual
// kinetic energy are in tests/validation/mps_hydrostatic_validation_test.cpp.
#include <catch2/catch.hpp>

#include "mps_support.hpp"

using namespace gf;

TEST_CASE("2D tank, l0 = H/20: time-averaged floor pressure within 3 % of rho g H, pressure rising with depth") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("hydrostatic_2d.toml"));
  const test::Samples s = test::run_and_sample(sim, 1500);  // 1.5 s
  const double rho_g_h = 1000.0 * 9.81 * 0.1;
  const double p = s.mean("bottom_pressure", 0.75);
  CAPTURE(p, s.rms("bottom_pressure", 0.75));
  // At 20 layers the top layer, held at p = 0 with a one-sided support, settles a fraction of l0 lower than a
  // full layer would: a bias of order l0/(2H) = 2.5 % (measured -2.2 %); the 2 % criterion is checked at
  // l0 = H/40 in the validation test.
  CHECK(p == Approx(rho_g_h).epsilon(0.03));
  // Settled: the kinetic energy left is a small fraction of the potential energy scale rho g H^2/2 * width
  // (9.8 J/m); the start-up transient peaks near 0.013 J/m.
  CHECK(s.mean("kinetic_energy", 0.75) < 1e-3);
  // Pressure increases with depth along the column in the middle of the tank.
  const FluidNodes& f = sim.nodes();
  double p_low = 0, p_mid = 0, n_low = 0, n_mid = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && std::abs(f.x[i] - 0.1) < 0.02) {
      if (f.y[i] < 0.02) p_low += f.p[i], n_low += 1;
      else if (f.y[i] > 0.045 && f.y[i] < 0.055) p_mid += f.p[i], n_mid += 1;
    }
  CHECK(p_low / n_low > p_mid / n_mid);
}
