// scenes/liquid/fluidised_bed.toml measured in-process for the fluidisation tests: the bed's height and
// liquid fraction from the beads' centres, the drag the liquid gives them over their weight, and the
// liquid's speed read at them, with Ergun's and Richardson-Zaki's references (as
// studies/seed003/fluidised_bed.py computes them for the README's sweep).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "systems/coupling/coupled_step.hpp"
#include "systems/setup/coupled_simulation.hpp"

namespace gf::test {

struct FluidisedBed {
  static constexpr double d = 2.0e-3, rho_p = 2500.0, rho_l = 1000.0, mu = 0.01, g = 9.81;
  static constexpr double area = 0.03 * 0.03, floor = 0.02;  // m^2, m: the column and the beads' floor
  static double volume() { return std::numbers::pi / 6.0 * d * d * d; }

  double height = 0;    // m, floor to the 99th percentile of the centres plus a radius
  double eps_bed = 0;   // 1 - N V / (A height)
  double eps_mid = 0;   // liquid fraction of the middle half of the height, beads counted by centre
  double drag = 0;      // (liquid force along the column - N V rho_l g) / (N V (rho_p - rho_l) g)
  double u = 0;         // m/s, the liquid's speed along the column read at the beads, mean
  double eps_read = 0;  // the liquid fraction read at the beads, mean
  double speed = 0;     // m/s, the beads' mean speed along the column

  double ergun_gradient(double u_sup, double eps) const {
    const double e3 = eps * eps * eps;
    return 150 * mu * (1 - eps) * (1 - eps) * u_sup / (e3 * d * d) + 1.75 * rho_l * (1 - eps) * u_sup * u_sup / (e3 * d);
  }
  // The superficial speed at which Ergun's gradient carries the beads' weight less buoyancy at liquid
  // fraction eps (bisection): the drag law's own expansion below eps = 0.8.
  double ergun_balance(double eps) const {
    const double target = (1 - eps) * (rho_p - rho_l) * g;
    double lo = 0, hi = 1;
    for (int k = 0; k < 100; ++k) ((ergun_gradient(0.5 * (lo + hi), eps) < target) ? lo : hi) = 0.5 * (lo + hi);
    return 0.5 * (lo + hi);
  }
  // Ergun's pressure drop over the bed at U = eps_mid u and eps_bed, over the beads' weight less buoyancy.
  double ergun(std::size_t n) const {
    return ergun_gradient(eps_mid * u, eps_bed) * height * area / (double(n) * volume() * (rho_p - rho_l) * g);
  }
};

inline FluidisedBed measure_bed(World& w) {
  Grains& gr = w.grains;  // extras are reached through a non-const table
  const std::size_t n = gr.n_owned;
  const LiquidForce& f = gr.extras.get<LiquidForce>();
  const LiquidAtGrain& at = gr.extras.get<LiquidAtGrain>();
  FluidisedBed b;
  std::vector<double> x(gr.pos.x.begin(), gr.pos.x.begin() + static_cast<std::ptrdiff_t>(n));
  std::sort(x.begin(), x.end());
  b.height = x[static_cast<std::size_t>(0.99 * double(n - 1))] + FluidisedBed::d / 2 - FluidisedBed::floor;
  const double lo = FluidisedBed::floor + 0.25 * b.height, hi = FluidisedBed::floor + 0.75 * b.height;
  const auto mid = std::count_if(x.begin(), x.end(), [&](double v) { return v >= lo && v < hi; });
  const double v = FluidisedBed::volume();
  b.eps_mid = 1 - double(mid) * v / (FluidisedBed::area * (hi - lo));
  b.eps_bed = 1 - double(n) * v / (FluidisedBed::area * b.height);
  double force = 0;
  for (std::size_t i = 0; i < n; ++i) {
    force += f.x[i];
    b.u += at.ux[i] / double(n);
    b.eps_read += at.eps[i] / double(n);
    b.speed += gr.vel.x[i] / double(n);
  }
  const double g = FluidisedBed::g;
  b.drag = (force - double(n) * v * FluidisedBed::rho_l * g) / (double(n) * v * (FluidisedBed::rho_p - FluidisedBed::rho_l) * g);
  return b;
}

// The scene at drive speed `u` (m/s) run for `seconds`; the bed measured over the last `window` s, every 10 steps.
inline FluidisedBed run_bed(double u, double seconds, double window) {
  CoupledSimulation sim = CoupledSimulation::from_file(std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/liquid/fluidised_bed.toml",
                                                       {"drive.mean_velocity=" + std::to_string(u)});
  const double dt = sim.scene().liquid.dt;
  const auto steps = std::llround(seconds / dt), sampled = std::llround(window / dt) / 10;
  sim.advance(steps - 10 * sampled);
  FluidisedBed mean;
  for (long long k = 0; k < sampled; ++k) {
    sim.advance(10);
    const FluidisedBed b = measure_bed(sim.world());
    mean.drag += b.drag / double(sampled);
    mean.u += b.u / double(sampled);
    mean.eps_read += b.eps_read / double(sampled);
    mean.speed += b.speed / double(sampled);
    mean.height = b.height, mean.eps_bed = b.eps_bed, mean.eps_mid = b.eps_mid;  // the geometry at the end
  }
  return mean;
}

}  // namespace gf::test
