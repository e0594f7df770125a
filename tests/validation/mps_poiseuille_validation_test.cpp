// Plane Poiseuille start-up flow, full runs: one diffusion time at l0 = L/20 and L/40; the centre velocity
// against the series solution, with the error reported against both the face-to-face width L and the
// wall-node-to-wall-node width L + l0 where the MPS Laplacian applies u = 0.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../mps_support.hpp"

using namespace gf;

namespace {
double startup_velocity(double y, double t, double f, double nu, double L) {
  const double pi = std::numbers::pi;
  double u = f / (2 * nu) * y * (L - y);
  for (int n = 1; n < 400; n += 2)
    u -= 4 * f * L * L / (nu * pi * pi * pi * n * n * n) * std::sin(n * pi * y / L) * std::exp(-n * n * pi * pi * nu * t / (L * L));
  return u;
}

// Worst relative error of the centre velocity over t >= 0.1 s, the wall taken `shift` outside each face.
double worst_error(const test::Samples& s, double l0, double shift) {
  const double f = 0.08, nu = 1e-4, L = 0.01 + 2 * shift;
  const std::size_t c = test::column_index("centre_velocity");
  double worst = 0;
  for (const auto& r : s.rows) {
    if (r[0] < 0.1) continue;
    const double ref = 0.5 * (startup_velocity(0.5 * L - 0.5 * l0, r[0], f, nu, L) + startup_velocity(0.5 * L + 0.5 * l0, r[0], f, nu, L));
    worst = std::max(worst, std::abs(r[c] - ref) / ref);
  }
  return worst;
}
}  // namespace

TEST_CASE("Poiseuille start-up to steady state at l0 = L/20 and L/40") {
  double prev_face = 1;
  for (double l0 : {5e-4, 2.5e-4}) {
    const double dt = l0 == 5e-4 ? 2.5e-4 : 6.25e-5;  // same diffusion number 0.1
    auto sim = LiquidSimulation::from_file(test::liquid_scene("poiseuille_2d.toml"),
                                           {"liquid.l0=" + std::to_string(l0), "run.dt=" + std::to_string(dt)});
    const std::int64_t steps = std::llround(1.0 / dt);
    const auto t0 = std::chrono::steady_clock::now();
    const test::Samples s = test::run_and_sample(sim, steps, std::llround(0.01 / dt));
    const test::LiquidCost cost = test::cost_of(sim, steps, test::seconds_since(t0));
    const double face = worst_error(s, l0, 0.0), node = worst_error(s, l0, 0.5 * l0);
    std::printf("Poiseuille l0 = L/%.0f: worst centre-velocity error %.2f %% (width L), %.2f %% (width L + l0)\n",
                0.01 / l0, 100 * face, 100 * node);
    // The centre velocity at the end of the run against the series at the wall-node width L + l0.
    const double t_end = s.rows.back()[0], u_end = s.rows.back()[test::column_index("centre_velocity")];
    const double Le = 0.01 + l0;
    const double u_ref = 0.5 * (startup_velocity(0.5 * Le - 0.5 * l0, t_end, 0.08, 1e-4, Le) +
                                startup_velocity(0.5 * Le + 0.5 * l0, t_end, 0.08, 1e-4, Le));
    const std::string name = "plane Poiseuille start-up, periodic channel L = 0.01 m, body force, l0 = L/" +
                             std::to_string(std::lround(0.01 / l0)) + ", diffusion number 0.1, centre velocity";
    const char* prog = "mps_poiseuille_validation_test";
    test::record_liquid(prog, name,
                        {"centre velocity at the last sample, t = " + test::csv_number(t_end, 4) + " s", "m/s",
                         "transient series, width L + l0", u_ref, u_end, 100 * (u_end / u_ref - 1), ""},
                        cost);
    test::record_liquid(prog, name,
                        {"worst |error| over 0.1-1 s", "", "transient series, width L (wall faces)", NAN, NAN,
                         100 * face, prev_face < 1 ? "< the L/20 run's" : ""},
                        cost);
    test::record_liquid(prog, name,
                        {"worst |error| over 0.1-1 s", "", "transient series, width L + l0 (wall-node centres)", NAN,
                         NAN, 100 * node, "< 3 %"},
                        cost);
    // With the no-slip width L + l0 the start-up curve matches within 3 % (measured under 2 % at L/20).
    CHECK(node < 0.03);
    // Against the face-to-face width the error is the wall offset, O(l0/L): it must shrink with l0.
    CHECK(face < prev_face);
    prev_face = face;
  }
}
