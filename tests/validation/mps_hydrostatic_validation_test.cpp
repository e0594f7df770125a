// Hydrostatic tanks, full validation: floor pressure time-averaged after settling, within 2 % of rho g H in 2D
// (l0 = H/40) and 3D (l0 = H/20), with the RMS pressure fluctuation and the residual kinetic energy reported.
#include <catch2/catch.hpp>

#include <cstdio>

#include "../mps_support.hpp"

using namespace gf;

namespace {
void report(const char* label, const test::Samples& s, double t0, double ref) {
  std::printf("%s: bottom pressure %.2f Pa (rho g H = %.2f Pa, error %+.2f %%), RMS fluctuation %.2f Pa, "
              "residual kinetic energy %.3e J\n",
              label, s.mean("bottom_pressure", t0), ref, 100 * (s.mean("bottom_pressure", t0) / ref - 1),
              s.rms("bottom_pressure", t0), s.mean("kinetic_energy", t0));
}

// Records the floor pressure, its RMS fluctuation and the kinetic energy left, averaged from t0 on, with the
// bounds the test checks them against.
void record(const std::string& case_name, const test::Samples& s, double t0, double ref, const std::string& rms_bound,
            const std::string& energy_unit, const test::LiquidCost& cost) {
  const double p = s.mean("bottom_pressure", t0);
  const char* prog = "mps_hydrostatic_validation_test";
  test::record_liquid(prog, case_name,
                      {"floor pressure", "Pa", "rho g H", ref, p, 100 * (p / ref - 1), "|error| < 2 %"}, cost);
  test::record_liquid(prog, case_name,
                      {"RMS fluctuation of the floor pressure", "Pa", "", NAN, s.rms("bottom_pressure", t0), NAN,
                       rms_bound},
                      cost);
  test::record_liquid(prog, case_name,
                      {"kinetic energy left", energy_unit, "", NAN, s.mean("kinetic_energy", t0), NAN, ""}, cost);
}
}  // namespace

TEST_CASE("2D tank, l0 = H/40: time-averaged floor pressure within 2 % of rho g H") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("hydrostatic_2d.toml"),
                                         {"liquid.l0=0.0025", "run.dt=5e-4", "run.duration=2.0"});
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, 4000, 10);
  const test::LiquidCost cost = test::cost_of(sim, 4000, test::seconds_since(t0));
  const double ref = 1000.0 * 9.81 * 0.1;
  report("hydrostatic 2D l0=H/40", s, 1.0, ref);
  record("hydrostatic tank 2D, H = 0.1 m, l0 = H/40, dt = 5e-4 s, mean over 1-2 s", s, 1.0, ref, "< 0.2 rho g H",
         "J/m", cost);
  // 2 %: the criterion; the surface-layer bias (~l0/(2H) at most) is 1.25 % at this resolution.
  CHECK(s.mean("bottom_pressure", 1.0) == Approx(ref).epsilon(0.02));
  // MPS pressure noise grows as l0 shrinks at a fixed CFL number: measured 0.6 % RMS at H/20, 13 % at H/40.
  // Bounded at 20 %: a pressure field that oscillates without settling exceeds it.
  CHECK(s.rms("bottom_pressure", 1.0) < 0.20 * ref);
}

TEST_CASE("3D tank, l0 = H/20, dt = 2.5e-4 s: time-averaged floor pressure within 2 % of rho g H") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("hydrostatic_3d.toml"));
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, 6000, 20);
  const test::LiquidCost cost = test::cost_of(sim, 6000, test::seconds_since(t0));
  const double ref = 1000.0 * 9.81 * 0.1;
  report("hydrostatic 3D l0=H/20", s, 0.75, ref);
  record("hydrostatic tank 3D, 0.1 m cube of water, l0 = H/20, dt = 2.5e-4 s (scene default), mean over 0.75-1.5 s",
         s, 0.75, ref, "< 0.05 rho g H", "J", cost);
  // The floor pressure's bias grows with dt (nodes crowd the floor more, so less pressure carries the same
  // weight): measured -4.2 % at dt = 1e-3 s, -2.1 % at 5e-4 s, -0.4 % at the scene's 2.5e-4 s.
  CHECK(s.mean("bottom_pressure", 0.75) == Approx(ref).epsilon(0.02));
  CHECK(s.rms("bottom_pressure", 0.75) < 0.05 * ref);
}
