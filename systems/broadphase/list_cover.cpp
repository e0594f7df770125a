#include "systems/broadphase/list_cover.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "engine/simd.hpp"

namespace gf {

namespace {

// True when rows a < b are a pair of the list (a owns it; its partners are a handful).
bool listed(const NeighborList& list, std::uint32_t a, std::uint32_t b) {
  for (std::uint32_t k = list.offsets[a]; k < list.offsets[a + 1]; ++k)
    if (list.j[k] == b) return true;
  return false;
}

// The larger of a and b, or NaN when either is (a non-finite position must reach the rebuild, whose
// grid build names the row).
double nan_max(double a, double b) { return a != a ? a : (b != b ? b : std::max(a, b)); }

}  // namespace

bool list_covers_contacts(const Grains& g, const double* rx, const double* ry, const double* rz, double skin,
                          const NeighborList& list, ListCover& scratch, double law_reach) {
  const std::size_t n = g.n_owned;
  if (list.offsets.size() != n + 1) return false;
  // Whole batches: the columns are padded with zeros in both tables (a padding row never moves).
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  auto d2_batch = [&](std::size_t i) {
    const B dx = B::load_aligned(&g.pos.x[i]) - B::load_aligned(rx + i);
    const B dy = B::load_aligned(&g.pos.y[i]) - B::load_aligned(ry + i);
    const B dz = B::load_aligned(&g.pos.z[i]) - B::load_aligned(rz + i);
    return dx * dx + dy * dy + dz * dz;
  };
  const std::size_t nb = (n + L - 1) / L;
  const double d2max = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nb, 512), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double m) {
        B mb(0.0), bad(0.0);
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
          const B d2 = d2_batch(b * L);
          mb = xsimd::max(mb, d2);
          bad += d2 - d2;  // NaN stays NaN
        }
        alignas(64) double lane[L], flag[L];
        mb.store_aligned(lane);
        bad.store_aligned(flag);
        for (std::size_t l = 0; l < L; ++l) m = nan_max(m, lane[l] + flag[l]);
        return m;
      },
      [](double a, double b) { return nan_max(a, b); });
  const double dmax = std::sqrt(d2max);
  // Movers: d > skin - D, collected per fixed block of rows and joined in row order. The bound is
  // lowered by 1e-9 of the skin, far above the round-off of the displacements (positions of order
  // metres, displacements and skin of order 1e-4 m), so a mover is never dropped by rounding; a row
  // that moved about a whole skin leaves no bound at all: rebuild.
  const double lo = skin * (1.0 - 1e-9) - dmax;
  if (!(lo > 0.0)) return false;  // also NaN
  const double lo2 = lo * lo;
  constexpr std::size_t kRows = 4096;
  const std::size_t nblocks = (n + kRows - 1) / kRows;
  scratch.blocks.resize(nblocks);
  static_assert(kRows % L == 0);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    std::vector<std::uint32_t>& out = scratch.blocks[b];
    out.clear();
    for (std::size_t i = b * kRows; i < std::min(n, (b + 1) * kRows); i += L) {
      std::uint32_t bits = lane_bits(d2_batch(i) > B(lo2));
      while (bits != 0) {
        out.push_back(static_cast<std::uint32_t>(i + static_cast<std::size_t>(__builtin_ctz(bits))));
        bits &= bits - 1u;
      }
    }
  });
  std::vector<std::uint32_t>& m = scratch.movers;
  m.clear();
  for (const auto& v : scratch.blocks) {
    if (m.size() + v.size() > n / 8) return false;
    m.insert(m.end(), v.begin(), v.end());
  }
  double rmax = 0.0;
  std::array<double, 3> bmin{INFINITY, INFINITY, INFINITY}, bmax{-INFINITY, -INFINITY, -INFINITY};
  for (std::uint32_t i : m) {
    rmax = std::max(rmax, g.radius.r[i]);
    const double p[3] = {g.pos.x[i], g.pos.y[i], g.pos.z[i]};
    for (int d = 0; d < 3; ++d) {
      bmin[d] = std::min(bmin[d], p[d]);
      bmax[d] = std::max(bmax[d], p[d]);
    }
  }
  if (m.size() < 2) return true;
  // Sort and sweep along the movers' widest axis: a touching pair is closer than r_a + r_max there.
  int ax = 0;
  for (int d = 1; d < 3; ++d)
    if (bmax[d] - bmin[d] > bmax[ax] - bmin[ax]) ax = d;
  const double* c = ax == 0 ? g.pos.x.data() : ax == 1 ? g.pos.y.data() : g.pos.z.data();
  std::sort(m.begin(), m.end(), [&](std::uint32_t a, std::uint32_t b) { return c[a] < c[b] || (c[a] == c[b] && a < b); });
  constexpr double kMargin = 1.0 + 1e-9;  // a pair at the kernel's own touching bound counts as touching
  for (std::size_t p = 0; p < m.size(); ++p) {
    const std::uint32_t a = m[p];
    const double reach = (g.radius.r[a] + rmax + law_reach) * kMargin;
    for (std::size_t q = p + 1; q < m.size() && c[m[q]] - c[a] < reach; ++q) {
      const std::uint32_t b = m[q];
      const double dx = g.pos.x[b] - g.pos.x[a], dy = g.pos.y[b] - g.pos.y[a], dz = g.pos.z[b] - g.pos.z[a];
      const double rs = (g.radius.r[a] + g.radius.r[b] + law_reach) * kMargin;
      if (dx * dx + dy * dy + dz * dz < rs * rs && !listed(list, std::min(a, b), std::max(a, b))) return false;
    }
  }
  return true;
}

}  // namespace gf
