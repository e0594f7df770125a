#include "systems/mps/number_density.hpp"

#include <cmath>
#include <cstdint>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/simd.hpp"
#include "systems/mps/kernel.hpp"
#include "systems/mps/pair_batch.hpp"

namespace gf {

// A row's pairs kLanes at a time (pair_batch.hpp), the rest one by one as NeighborPairs::rel and zhang_weight
// compute them; the row's sum adds the weights lane by lane.
void compute_number_density(FluidNodes& f, NeighborPairs& nb, double re) {
  const PairBatches pairs(f, nb);
  const BatchD vre(re), a(0.85), b(0.15 * re), one(1.0), zero(0.0);
  double* w = nb.w.data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      std::uint32_t k = nb.start[i];
      const std::uint32_t end = nb.start[i + 1];
      BatchD acc(0.0);
      for (; k + kLanes <= end; k += kLanes) {
        BatchD dx, dy, dz;
        pairs.rel(i, k, dx, dy, dz);
        const BatchD dist = xsimd::sqrt(dx * dx + dy * dy + dz * dz);
        const BatchD wk = xsimd::select(dist < vre, vre / (a * dist + b) - one, zero);
        wk.store_unaligned(w + k);
        acc += wk;
      }
      double tail = 0;
      for (; k < end; ++k) {
        double dx, dy, dz;
        nb.rel(f, i, k, dx, dy, dz);
        w[k] = zhang_weight(std::sqrt(dx * dx + dy * dy + dz * dz), re);
        tail += w[k];
      }
      f.n[i] = xsimd::hadd(acc) + tail;
    }
  });
}

}  // namespace gf
