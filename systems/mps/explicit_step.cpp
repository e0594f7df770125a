#include "systems/mps/explicit_step.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

void mps_laplacian(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, const ColumnD& phi,
                   ColumnD& out) {
  const double c = k.lap_coef();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      double s = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) s += (phi[nb.j[q]] - phi[i]) * nb.w[q];
      out[i] = c * s;
    }
  });
}

void predict_velocity(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt,
                      std::span<const double> eps, std::span<const double> nut) {
  const std::size_t n = f.size();
  const double nu = lp.nu + lp.eddy_viscosity;
  const double lap = lp.k.lap_coef();
  const double c = nu * lap;
  const double gx = lp.gravity[0] + lp.body_force[0];
  const double gy = lp.gravity[1] + lp.body_force[1];
  const double gz = lp.gravity[2] + lp.body_force[2];
  // Wall and dummy velocities are zero, so (u_j - u_i) with u_j = 0 is the no-slip condition.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      double sx = 0, sy = 0, sz = 0;
      double ci = eps.empty() ? c : c / eps[i];  // a locally averaged liquid's n~0 = eps n0
      if (nut.empty()) {
        for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
          const std::uint32_t j = nb.j[q];
          const double w = nb.w[q];
          sx += (f.u[j] - f.u[i]) * w;
          sy += (f.v[j] - f.v[i]) * w;
          sz += (f.w[j] - f.w[i]) * w;
        }
      } else {
        // Pair by pair nu + nu_t,ij (mixing_length.hpp), the pair's viscosity inside the sum.
        for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
          const std::uint32_t j = nb.j[q];
          const double w = nb.w[q] * (nu + (f.kind[j] == kFluid ? 0.5 * (nut[i] + nut[j]) : nut[i]));
          sx += (f.u[j] - f.u[i]) * w;
          sy += (f.v[j] - f.v[i]) * w;
          sz += (f.w[j] - f.w[i]) * w;
        }
        ci = eps.empty() ? lap : lap / eps[i];
      }
      f.ax[i] = ci * sx + gx;
      f.ay[i] = ci * sy + gy;
      f.az[i] = ci * sz + gz;
    }
  });
  const bool three = lp.k.dim == 3;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      f.u[i] += dt * f.ax[i];
      f.v[i] += dt * f.ay[i];
      if (three) f.w[i] += dt * f.az[i];
      f.x[i] += dt * f.u[i];
      f.y[i] += dt * f.v[i];
      f.z[i] += dt * f.w[i];
    }
  });
}

}  // namespace gf
