// Periodic pipe driven by a body force (scenes/liquid/pipe_3d.toml, R = 10 l0): the centre velocity after two
// diffusion times against Hagen-Poiseuille, u_c = f R^2 / (4 nu) = 2.5e-3 m/s. Exercises the 3D pipe walls, the
// periodic axis and the closed (no free surface) PPE in 3D.
#include <catch2/catch.hpp>

#include <cstdio>

#include "../mps_support.hpp"

using namespace gf;

TEST_CASE("3D periodic pipe: steady centre velocity near Hagen-Poiseuille") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("pipe_3d.toml"));
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, 2000, 40);
  const test::LiquidCost cost = test::cost_of(sim, 2000, test::seconds_since(t0));
  const double uc = s.rows.back()[test::column_index("centre_velocity")];
  const double ref = 0.04 * 0.005 * 0.005 / (4 * 1e-4);
  std::printf("pipe 3D R=10 l0: centre velocity %.4g m/s, Hagen-Poiseuille %.4g m/s (%+.1f %%)\n", uc, ref,
              100 * (uc / ref - 1));
  const double u_before = s.rows[s.rows.size() - 11][test::column_index("centre_velocity")];
  const std::string name = "periodic pipe 3D, R = 5 mm = 10 l0, body force, centre velocity after 2 diffusion times";
  test::record_liquid("mps_pipe_validation_test", name,
                      {"centre velocity at t = 0.5 s", "m/s", "Hagen-Poiseuille f R^2/(4 nu)", ref, uc,
                       100 * (uc / ref - 1), "|error| < 15 %, above the reference"},
                      cost);
  test::record_liquid("mps_pipe_validation_test", name,
                      {"change of the centre velocity over the last 0.1 s", "", "", NAN, NAN,
                       100 * (uc / u_before - 1), "|change| < 1 %"},
                      cost);
  // As in the plane channel, u = 0 enters at the wall nodes' centres (R to R + l0 from the axis), so the
  // discrete bore is wider than R by a fraction of l0: measured +8.8 % at R = 10 l0 (plane channel, same
  // effect: +12 % at L = 20 l0). 15 % still rejects a missing wall layer or a wrong viscous term.
  CHECK(uc == Approx(ref).epsilon(0.15));
  CHECK(uc > ref);  // the offset widens the bore, never narrows it
  // Steady: the last 0.1 s changes the centre velocity by under 1 %.
  const auto& rows = s.rows;
  CHECK(std::abs(rows.back()[test::column_index("centre_velocity")] / rows[rows.size() - 11][test::column_index("centre_velocity")] - 1) < 0.01);
}
