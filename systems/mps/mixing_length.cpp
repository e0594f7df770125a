#include "systems/mps/mixing_length.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

double nikuradse_length(double y_over_r) {
  const double s = 1.0 - std::clamp(y_over_r, 0.0, 1.0);
  const double s2 = s * s;
  return 0.14 - 0.08 * s2 - 0.06 * s2 * s2;
}

void mixing_length_viscosity(const FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp,
                             std::vector<double>& nut) {
  const MixingLength& ml = lp.mixing_length;
  const double c = lp.k.grad_coef();
  nut.assign(f.size(), 0.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kFluid) continue;
      double g[3][3] = {};  // g[a][b] = d u_b / d x_a
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
        const double w = nb.w[q];
        if (w == 0) continue;
        double d[3];
        nb.rel(f, i, q, d[0], d[1], d[2]);
        const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        if (!(r2 > 0)) continue;
        const std::uint32_t j = nb.j[q];
        const double du[3] = {f.u[j] - f.u[i], f.v[j] - f.v[i], f.w[j] - f.w[i]};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) g[a][b] += du[b] * d[a] / r2 * w;
      }
      double ss = 0;  // 2 S:S
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
          const double s = 0.5 * c * (g[a][b] + g[b][a]);
          ss += 2.0 * s * s;
        }
      const double ry = f.y[i] - ml.cy, rz = f.z[i] - ml.cz;
      const double y = ml.radius - std::sqrt(ry * ry + rz * rz);
      const double lm = ml.radius * nikuradse_length(y / ml.radius);
      nut[i] = lm * lm * std::sqrt(ss);
    }
  });
}

}  // namespace gf
