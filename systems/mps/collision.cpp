#include "systems/mps/collision.hpp"

#include <atomic>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

std::size_t apply_collisions(FluidNodes& f, const NeighborPairs& nb, const CollisionSettings& c, double dt) {
  if (!(c.distance > 0)) return 0;
  const double d2 = c.distance * c.distance;
  std::atomic<std::size_t> hits{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    std::size_t local = 0;
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      double du = 0, dv = 0, dw = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
        double dx, dy, dz;
        nb.rel(f, i, q, dx, dy, dz);
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 >= d2 || !(r2 > 0)) continue;
        const std::uint32_t j = nb.j[q];
        const double inv = 1.0 / std::sqrt(r2);
        const double nx = dx * inv, ny = dy * inv, nz = dz * inv;
        const double w = (f.u[i] - f.u[j]) * nx + (f.v[i] - f.v[j]) * ny + (f.w[i] - f.w[j]) * nz;
        if (w <= 0) continue;
        const double s = (f.kind[j] == kFluid ? 0.5 : 1.0) * (1.0 + c.restitution) * w;
        du -= s * nx;
        dv -= s * ny;
        dw -= s * nz;
        ++local;
      }
      f.ax[i] = du;
      f.ay[i] = dv;
      f.az[i] = f.dim == 3 ? dw : 0.0;
    }
    hits += local;
  });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      f.u[i] += f.ax[i];
      f.v[i] += f.ay[i];
      f.w[i] += f.az[i];
      f.x[i] += dt * f.ax[i];
      f.y[i] += dt * f.ay[i];
      f.z[i] += dt * f.az[i];
    }
  });
  return hits.load();
}

}  // namespace gf
