#include "systems/mps/pressure_gradient.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

void mps_gradient(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, GradientForm form,
                  const ColumnD& phi, ColumnD& gx, ColumnD& gy, ColumnD& gz, bool fluid_only) {
  const double c = k.grad_coef();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] == kDummy || (fluid_only && f.kind[i] != kFluid)) continue;
      double base = phi[i];
      if (form == GradientForm::MinPressure) {
        for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q)
          if (nb.w[q] > 0) base = std::min(base, phi[nb.j[q]]);
      }
      double sx = 0, sy = 0, sz = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
        const double w = nb.w[q];
        if (w == 0) continue;
        double dx, dy, dz;
        nb.rel(f, i, q, dx, dy, dz);
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (!(r2 > 0)) continue;
        const double pj = phi[nb.j[q]];
        const double a = (form == GradientForm::Sum ? pj + base : pj - base) / r2 * w;
        sx += a * dx;
        sy += a * dy;
        sz += a * dz;
      }
      gx[i] = c * sx;
      gy[i] = c * sy;
      gz[i] = c * sz;
    }
  });
}

void correct_velocity(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt) {
  mps_gradient(f, nb, lp.k, lp.gradient, f.p, f.ax, f.ay, f.az, true);
  const double s = -dt / lp.rho;
  const bool three = lp.k.dim == 3;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      const double du = s * f.ax[i], dv = s * f.ay[i], dw = three ? s * f.az[i] : 0.0;
      f.u[i] += du;
      f.v[i] += dv;
      f.w[i] += dw;
      f.x[i] += dt * du;
      f.y[i] += dt * dv;
      f.z[i] += dt * dw;
    }
  });
}

}  // namespace gf
