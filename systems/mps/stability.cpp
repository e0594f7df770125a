#include "systems/mps/stability.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace gf {

namespace {
std::string num(double v) {
  char b[48];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}
std::string where(const FluidNodes& f, std::size_t i) {
  return "node " + std::to_string(i) + " at (" + num(f.x[i]) + ", " + num(f.y[i]) + (f.dim == 3 ? ", " + num(f.z[i]) : "") +
         ") m";
}
}  // namespace

void check_ppe(const PpeResult& r, const PpeSettings& s, double t) {
  if (r.converged) return;
  throw LiquidFailure("pressure solver failed at t = " + num(t) + " s: relative residual " + num(r.residual) +
                      " after " + std::to_string(r.iterations) + " iterations (" + std::to_string(r.unknowns) +
                      " unknowns), limit liquid.solver.tolerance = " + num(s.tolerance) + " within max_iterations = " +
                      std::to_string(s.max_iterations) +
                      ". Fix: reduce run.dt, or raise liquid.solver.max_iterations (a solve from rest needs about "
                      "as many iterations as there are nodes across the domain, several times more), or try "
                      "liquid.solver = { kind = \"eigen_cg\", preconditioner = \"incomplete_cholesky\" }");
}

void check_density(const FluidNodes& f, const LiquidParams& lp, const StabilityLimits& lim, double t,
                   LiquidDiagnostics& d) {
  double worst = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && !(f.n[i] <= worst)) {
      worst = f.n[i];
      at = i;
    }
  d.max_density_ratio = worst / lp.k.n0;
  if (!(d.max_density_ratio <= lim.density_ratio))
    throw LiquidFailure("number-density spike at t = " + num(t) + " s: n*/n0 = " + num(d.max_density_ratio) + " at " +
                        where(f, at) + ", limit run.density_limit = " + num(lim.density_ratio) +
                        " (particles are being crushed together). Fix: reduce run.dt, or raise "
                        "liquid.gamma to correct density drift harder");
}

void check_motion(const FluidNodes& f, const LiquidParams& lp, const StabilityLimits& lim, double dt, double t,
                  LiquidDiagnostics& d) {
  double vmax2 = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] != kFluid) continue;
    const double s2 = f.u[i] * f.u[i] + f.v[i] * f.v[i] + f.w[i] * f.w[i];
    const double c[3] = {f.x[i], f.y[i], f.z[i]};
    bool inside = std::isfinite(s2);
    for (int a = 0; a < lp.k.dim; ++a) inside = inside && c[a] >= lim.lo[a] && c[a] <= lim.hi[a];
    if (!inside)
      throw LiquidFailure("particle left the domain at t = " + num(t) + " s: " + where(f, i) + ", speed " +
                          num(std::sqrt(s2)) + " m/s, outside the geometry's bounds [" + num(lim.lo[0]) + ", " +
                          num(lim.hi[0]) + "] x [" + num(lim.lo[1]) + ", " + num(lim.hi[1]) +
                          "] m (plus run.domain_margin). Fix: reduce run.dt, or enlarge the geometry or "
                          "run.domain_margin if the splash is physical");
    if (s2 > vmax2) {
      vmax2 = s2;
      at = i;
    }
  }
  d.max_speed = std::sqrt(vmax2);
  d.cfl = d.max_speed * dt / lp.k.l0;
  if (!(d.cfl <= lim.cfl))
    throw LiquidFailure("CFL limit broken at t = " + num(t) + " s: max |u| dt / l0 = " + num(d.cfl) + " (|u| = " +
                        num(d.max_speed) + " m/s at " + where(f, at) + "), limit run.cfl_limit = " + num(lim.cfl) +
                        ". Fix: reduce run.dt below " + num(lim.cfl * lp.k.l0 / d.max_speed) + " s");
}

}  // namespace gf
