// Plane Poiseuille start-up flow (scenes/liquid/poiseuille_2d.toml), short version: periodic channel driven by a
// body force, centre-line velocity against the transient series solution up to t = 0.3 s (0.3 diffusion times).
// The full run to steady state and the finer resolution are in tests/validation/mps_poiseuille_validation_test.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "mps_support.hpp"

using namespace gf;

namespace {
// Start-up plane Poiseuille flow between no-slip plates at y = 0 and y = L (fluid at rest at t = 0).
double startup_velocity(double y, double t, double f, double nu, double L) {
  const double pi = std::numbers::pi;
  double u = f / (2 * nu) * y * (L - y);
  for (int n = 1; n < 400; n += 2)
    u -= 4 * f * L * L / (nu * pi * pi * pi * n * n * n) * std::sin(n * pi * y / L) * std::exp(-n * n * pi * pi * nu * t / (L * L));
  return u;
}
}  // namespace

TEST_CASE("Poiseuille start-up: centre velocity follows the series solution, no-slip at the wall-node centres") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("poiseuille_2d.toml"));
  const double f = 0.08, nu = 1e-4, L = 0.01, l0 = 5e-4;
  const test::Samples s = test::run_and_sample(sim, 1200, 40);  // 0.3 s
  const std::size_t c = test::column_index("centre_velocity");
  for (const auto& r : s.rows) {
    const double t = r[0];
    if (t < 0.05) continue;
    // The wall velocity u = 0 enters the MPS Laplacian at the wall nodes' centres, l0/2 outside each wall face:
    // the discrete channel is L + l0 wide. The sampled nodes sit l0/2 either side of the centre line.
    const double Le = L + l0;
    const double ref = 0.5 * (startup_velocity(0.5 * Le - 0.5 * l0, t, f, nu, Le) + startup_velocity(0.5 * Le + 0.5 * l0, t, f, nu, Le));
    CAPTURE(t, r[c], ref);
    // 3 %: measured within 1.1 % up to 0.3 s at l0 = L/20 (the Laplacian's wall truncation); 3 % still rejects
    // the width L itself (10 % lower) and any error in the viscous or body-force terms.
    CHECK(r[c] == Approx(ref).epsilon(0.03));
  }
  // The flow stays parallel: transverse velocities tiny against the axial ones.
  const FluidNodes& nodes = sim.nodes();
  double vmax = 0, umax = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes.kind[i] == kFluid) {
      vmax = std::max(vmax, std::abs(nodes.v[i]));
      umax = std::max(umax, std::abs(nodes.u[i]));
    }
  CHECK(vmax < 0.05 * umax);
}

TEST_CASE("an eddy viscosity acts as viscosity in the momentum equation: nu = 1e-4 against 5e-5 + 5e-5") {
  // The same channel, its viscosity split in two halves: nu + nu_t is the same double (5e-5 doubled exactly),
  // so the two runs must agree bit for bit, row by row of the series.
  auto plain = LiquidSimulation::from_file(test::liquid_scene("poiseuille_2d.toml"));
  auto split = LiquidSimulation::from_file(test::liquid_scene("poiseuille_2d.toml"),
                                           {"liquid.viscosity=5.0e-5", "liquid.eddy_viscosity=5.0e-5"});
  REQUIRE(split.params().nu + split.params().eddy_viscosity == plain.params().nu);
  const test::Samples a = test::run_and_sample(plain, 200, 40), b = test::run_and_sample(split, 200, 40);
  REQUIRE(a.rows.size() == b.rows.size());
  const std::size_t c = test::column_index("centre_velocity");
  for (std::size_t k = 0; k < a.rows.size(); ++k) {
    CAPTURE(k, a.rows[k][c], b.rows[k][c]);
    CHECK(a.rows[k][c] == b.rows[k][c]);
  }
  CHECK(a.rows.back()[c] > 0);
}
