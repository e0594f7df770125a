#include "systems/mps/number_density.hpp"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "systems/mps/kernel.hpp"

namespace gf {

void compute_number_density(FluidNodes& f, NeighborPairs& nb, double re) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      double s = 0;
      for (std::uint32_t k = nb.start[i]; k < nb.start[i + 1]; ++k) {
        double dx, dy, dz;
        nb.rel(f, i, k, dx, dy, dz);
        const double w = zhang_weight(std::sqrt(dx * dx + dy * dy + dz * dz), re);
        nb.w[k] = w;
        s += w;
      }
      f.n[i] = s;
    }
  });
}

}  // namespace gf
