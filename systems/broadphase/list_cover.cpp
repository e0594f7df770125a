#include "systems/broadphase/list_cover.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "engine/simd.hpp"

namespace gf {

namespace {

// The larger of a and b, or NaN when either is.
double nan_max(double a, double b) { return a != a ? a : (b != b ? b : std::max(a, b)); }

// Squared displacements of the kLanes rows from row i (whole batches: the columns are padded with
// zeros in both tables, and a padding row never moves).
BatchD displacement2(const Grains& g, const double* rx, const double* ry, const double* rz, std::size_t i) {
  const BatchD dx = BatchD::load_aligned(&g.pos.x[i]) - BatchD::load_aligned(rx + i);
  const BatchD dy = BatchD::load_aligned(&g.pos.y[i]) - BatchD::load_aligned(ry + i);
  const BatchD dz = BatchD::load_aligned(&g.pos.z[i]) - BatchD::load_aligned(rz + i);
  return dx * dx + dy * dy + dz * dz;
}

}  // namespace

double largest_displacement2(const Grains& g, const double* rx, const double* ry, const double* rz) {
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const std::size_t nb = (g.n_owned + L - 1) / L;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nb, 512), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double m) {
        B mb(0.0), bad(0.0);
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
          const B d2 = displacement2(g, rx, ry, rz, b * L);
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
}

// Positions are of order metres, displacements and the skin of order 1e-4 m: 1e-9 of the skin is
// far above their round-off. A row that moved about a whole skin leaves no bound at all.
double mover_bound(double skin, double d2max) { return skin * (1.0 - 1e-9) - std::sqrt(d2max); }

bool collect_movers(const Grains& g, const double* rx, const double* ry, const double* rz, double bound,
                    std::size_t cap, ListCover& scratch) {
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const std::size_t n = g.n_owned;
  const double lo2 = bound * bound;
  // Collected per fixed block of rows and joined in row order.
  constexpr std::size_t kRows = 4096;
  static_assert(kRows % L == 0);
  const std::size_t nblocks = (n + kRows - 1) / kRows;
  scratch.blocks.resize(nblocks);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    std::vector<std::uint32_t>& out = scratch.blocks[b];
    out.clear();
    for (std::size_t i = b * kRows; i < std::min(n, (b + 1) * kRows); i += L) {
      std::uint32_t bits = lane_bits(displacement2(g, rx, ry, rz, i) > B(lo2));
      while (bits != 0) {
        const std::size_t row = i + static_cast<std::size_t>(__builtin_ctz(bits));
        if (row < n) out.push_back(static_cast<std::uint32_t>(row));
        bits &= bits - 1u;
      }
    }
  });
  std::vector<std::uint32_t>& m = scratch.movers;
  m.clear();
  for (const auto& v : scratch.blocks) {
    if (m.size() + v.size() > cap) return false;
    m.insert(m.end(), v.begin(), v.end());
  }
  return true;
}

double sort_along_widest_axis(std::vector<MoverPoint>& m) {
  double rmax = 0.0;
  std::array<double, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  for (const MoverPoint& p : m) {
    rmax = std::max(rmax, p.r);
    const double c[3] = {p.x, p.y, p.z};
    for (std::size_t d = 0; d < 3; ++d) lo[d] = std::min(lo[d], c[d]), hi[d] = std::max(hi[d], c[d]);
  }
  std::size_t ax = 0;
  for (std::size_t d = 1; d < 3; ++d)
    if (hi[d] - lo[d] > hi[ax] - lo[ax]) ax = d;
  for (MoverPoint& p : m) {
    if (ax == 1) std::tie(p.x, p.y, p.z) = std::make_tuple(p.y, p.z, p.x);
    if (ax == 2) std::tie(p.x, p.y, p.z) = std::make_tuple(p.z, p.x, p.y);
  }
  std::sort(m.begin(), m.end(), [](const MoverPoint& a, const MoverPoint& b) { return a.x < b.x || (a.x == b.x && a.id < b.id); });
  return rmax;
}

bool listed_under(const NeighborList& list, std::uint32_t owner, std::uint64_t key) {
  for (std::uint32_t k = list.offsets[owner]; k < list.offsets[owner + 1]; ++k)
    if (list.key[k] == key) return true;
  return false;
}

bool list_covers_contacts(const Grains& g, const double* rx, const double* ry, const double* rz, double skin,
                          const NeighborList& list, ListCover& scratch, double law_reach) {
  const std::size_t n = g.n_owned;
  if (list.offsets.size() != n + 1) return false;
  const double bound = mover_bound(skin, largest_displacement2(g, rx, ry, rz));
  if (!(bound > 0.0)) return false;  // also NaN
  if (!collect_movers(g, rx, ry, rz, bound, n / 8, scratch)) return false;
  if (scratch.movers.size() < 2) return true;
  std::vector<MoverPoint>& points = scratch.points;
  points.clear();
  for (const std::uint32_t i : scratch.movers)
    points.push_back({g.pos.x[i], g.pos.y[i], g.pos.z[i], g.radius.r[i], g.pid.id[i], i, 0});
  return each_touching_pair(points, law_reach, [&](const MoverPoint& a, const MoverPoint& b) {
    return listed_under(list, std::min(a.row, b.row), pair_key(a.id, b.id));
  });
}

}  // namespace gf
