#include "systems/mps/pressure_gradient.hpp"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "systems/mps/pair_batch.hpp"

namespace gf {

// A row's pairs kLanes at a time (pair_batch.hpp), the rest one by one; pairs at zero distance or zero weight
// add nothing (masked before the division), and the "min" form's base is the least phi among the row's
// weighted neighbours and the node itself.
void mps_gradient(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, GradientForm form,
                  const ColumnD& phi, ColumnD& gx, ColumnD& gy, ColumnD& gz, bool fluid_only) {
  const double c = k.grad_coef();
  const PairBatches pairs(f, nb);
  const BatchD zero(0.0), one(1.0);
  const double* w = nb.w.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] == kDummy || (fluid_only && f.kind[i] != kFluid)) continue;
      const std::uint32_t q0 = nb.start[i], end = nb.start[i + 1];
      double base = phi[i];
      if (form == GradientForm::MinPressure) {
        for (std::uint32_t q = q0; q < end; ++q)
          if (w[q] > 0) base = std::min(base, phi[nb.j[q]]);
      }
      const BatchD vbase(base), sign(form == GradientForm::Sum ? 1.0 : -1.0);
      BatchD ax(0.0), ay(0.0), az(0.0);
      std::uint32_t q = q0;
      for (; q + kLanes <= end; q += kLanes) {
        BatchD dx, dy, dz;
        pairs.rel(i, q, dx, dy, dz);
        const BatchD r2 = dx * dx + dy * dy + dz * dz;
        const BatchD wq = BatchD::load_unaligned(w + q);
        const auto on = (r2 > zero) && (wq != zero);
        const BatchD a = xsimd::select(on, (pairs.neighbours(phi.data(), q) + sign * vbase) / xsimd::select(on, r2, one) * wq, zero);
        ax += a * dx;
        ay += a * dy;
        az += a * dz;
      }
      double sx = 0, sy = 0, sz = 0;
      for (; q < end; ++q) {
        if (w[q] == 0) continue;
        double dx, dy, dz;
        nb.rel(f, i, q, dx, dy, dz);
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (!(r2 > 0)) continue;
        const double pj = phi[nb.j[q]];
        const double a = (form == GradientForm::Sum ? pj + base : pj - base) / r2 * w[q];
        sx += a * dx;
        sy += a * dy;
        sz += a * dz;
      }
      gx[i] = c * (xsimd::hadd(ax) + sx);
      gy[i] = c * (xsimd::hadd(ay) + sy);
      gz[i] = c * (xsimd::hadd(az) + sz);
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
