// Run-time stability detectors of the liquid. Each one stops the run with a LiquidFailure whose message names the
// limit that broke, where and when, and what to change. Checked every step:
//   - PPE solver failure (no convergence within max_iterations, or a non-finite residual);
//   - number-density spike: max n*/n0 over fluid nodes above run.density_limit (particles crushed together);
//   - CFL: max |u| dt / l0 above run.cfl_limit;
//   - a non-finite or escaped particle: a fluid node outside the geometry's bounds (plus run.domain_margin).
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/ppe.hpp"

namespace gf {

class LiquidFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StabilityLimits {
  double cfl = 0.5;            // max |u| dt / l0
  double density_ratio = 1.5;  // max n*/n0 of a fluid node
  std::array<double, 3> lo{}, hi{};  // m, fluid nodes must stay inside
};

struct LiquidDiagnostics {
  double max_speed = 0;          // m/s
  double cfl = 0;                // max |u| dt / l0
  double max_density_ratio = 0;  // max n*/n0 over fluid nodes, this step
  std::size_t surface_nodes = 0;
  PpeResult ppe;
  // Over this process's steps (not checkpointed): the PPE solves and their iterations summed.
  std::int64_t ppe_solves = 0;
  double ppe_iterations_total = 0;
};

// Throws if the solve failed; `t` is the simulated time (s) for the message.
void check_ppe(const PpeResult& r, const PpeSettings& s, double t);
// Max n*/n0 over fluid rows into d; throws above the limit.
void check_density(const FluidNodes& f, const LiquidParams& lp, const StabilityLimits& lim, double t,
                   LiquidDiagnostics& d);
// Speed, CFL and domain (and NaN) after the correction; throws on a broken limit.
void check_motion(const FluidNodes& f, const LiquidParams& lp, const StabilityLimits& lim, double dt, double t,
                  LiquidDiagnostics& d);

}  // namespace gf
