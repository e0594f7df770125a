#include "systems/mps/liquid_observables.hpp"

#include <cmath>
#include <limits>

namespace gf {

std::vector<std::string> liquid_series_columns() {
  return {"time",           "kinetic_energy", "max_speed",   "cfl",         "max_density_ratio", "surface_nodes",
          "ppe_iterations", "ppe_residual",   "surge_front", "bottom_pressure", "centre_velocity",
          "mean_velocity",  "body_force"};
}

double liquid_kinetic_energy(const FluidNodes& f, const LiquidParams& lp) {
  const double m = lp.rho * std::pow(lp.k.l0, lp.k.dim);
  double e = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid) e += 0.5 * m * (f.u[i] * f.u[i] + f.v[i] * f.v[i] + f.w[i] * f.w[i]);
  return e;
}

std::vector<double> sample_liquid(World& w, const LiquidScene& s) {
  const FluidNodes& f = w.tables.get<FluidNodes>();
  const LiquidParams& lp = w.resources.get<LiquidParams>();
  const LiquidDiagnostics& d = w.resources.get<LiquidDiagnostics>();
  const LiquidGeometry& g = s.geometry;
  const double l0 = lp.k.l0;
  const bool three = lp.k.dim == 3;

  double front = -std::numeric_limits<double>::infinity();
  double pb = 0, nb = 0, uc = 0, nc = 0, vmax2 = 0;
  const double xq0 = g.lo[0] + 0.25 * (g.hi[0] - g.lo[0]), xq1 = g.lo[0] + 0.75 * (g.hi[0] - g.lo[0]);
  const double zq0 = g.lo[2] + 0.25 * (g.hi[2] - g.lo[2]), zq1 = g.lo[2] + 0.75 * (g.hi[2] - g.lo[2]);
  const double yc = g.kind == LiquidGeometry::Kind::Pipe ? g.center[1] : 0.5 * (g.lo[1] + g.hi[1]);
  const double zc = g.kind == LiquidGeometry::Kind::Pipe ? g.center[2] : 0.5 * (g.lo[2] + g.hi[2]);
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] == kDummy) continue;
    const bool floor_band = f.kind[i] == kWall && f.y[i] < g.lo[1] && f.y[i] > g.lo[1] - l0 && f.x[i] > xq0 && f.x[i] < xq1 &&
                            (!three || (f.z[i] > zq0 && f.z[i] < zq1));
    if (floor_band) {
      pb += f.p[i];
      nb += 1;
    }
    if (f.kind[i] != kFluid) continue;
    // Isolated droplets are not the front (n is zero before the first step: no filter then).
    if (w.clock.step == 0 || f.n[i] >= 0.5 * lp.k.n0) front = std::max(front, f.x[i]);
    vmax2 = std::max(vmax2, f.u[i] * f.u[i] + f.v[i] * f.v[i] + f.w[i] * f.w[i]);
    if (std::abs(f.y[i] - yc) < l0 && (!three || std::abs(f.z[i] - zc) < l0)) {
      uc += f.u[i];
      nc += 1;
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double vmax = std::sqrt(vmax2);
  const int axis = std::max(lp.periodic.axis, 0);  // along the periodic axis, else x
  return {w.clock.t,
          liquid_kinetic_energy(f, lp),
          vmax,
          vmax * w.clock.dt / l0,
          d.max_density_ratio,
          static_cast<double>(d.surface_nodes),
          static_cast<double>(d.ppe.iterations),
          d.ppe.residual,
          front + 0.5 * l0,
          nb > 0 ? pb / nb : nan,
          nc > 0 ? uc / nc : nan,
          mean_fluid_velocity(f, axis),
          lp.body_force[static_cast<std::size_t>(axis)]};
}

}  // namespace gf
