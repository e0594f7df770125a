#include "systems/broadphase/pair_search.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "engine/simd.hpp"

namespace gf {

namespace {

// Distance from coordinate v to the cell interval [o + k cell, o + (k + 1) cell] along one axis.
inline double gap_to(double v, double o, std::int64_t k, double cell) {
  const double lo = o + static_cast<double>(k) * cell;
  return v < lo ? lo - v : std::max(0.0, v - (lo + cell));
}

// Cell index along one axis of coordinate v, which may lie outside the grid: kept within one reach
// of it, so that the range [k - ext, k + ext] clipped to the grid is right and no cast overflows.
inline std::int64_t cell_index(double v, double o, double inv_cell, std::int64_t dims, std::int64_t ext) {
  const double k = std::floor((v - o) * inv_cell);
  return static_cast<std::int64_t>(std::clamp(k, -static_cast<double>(ext) - 1.0, static_cast<double>(dims + ext)));
}

// A query: a point on the grid's axes, its cell, its radius and reach, and which sorted points
// count: those in [lo, hi) with radius at most `keep`.
struct Query {
  double x, y, z, r;
  std::int64_t cx, cy, cz;
  double reach, skin, keep;
  std::size_t lo, hi;
};

// Calls hit(s) for every sorted point s of `grid` (coordinates px, py, pz on its axes, radius rad,
// padded columns in its cell order) within r + r_s + skin of the query. Lines of cells along grid
// axis 0 within reach are culled by their distance in y and z; their cells are consecutive, so
// their points are one range, read in whole aligned batches with the lanes outside the range masked
// off. Hits are rare (a few in a hundred), so they are handed on bit by bit.
template <class Hit>
[[gnu::always_inline]] inline void scan(const CellGrid& grid, const double* px, const double* py, const double* pz,
                                        const double* rad, const Query& q, Hit&& hit) {
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const auto& dims = grid.dims;
  const auto ext = static_cast<std::int64_t>(std::ceil(q.reach / grid.cell));
  const B bx(q.x), by(q.y), bz(q.z), brs(q.r + q.skin), bkeep(q.keep);
  for (std::int64_t dz = -ext; dz <= ext; ++dz) {
    const std::int64_t zc = q.cz + dz;
    if (zc < 0 || zc >= dims[2]) continue;
    const double gz = gap_to(q.z, grid.origin[2], zc, grid.cell);
    for (std::int64_t dy = -ext; dy <= ext; ++dy) {
      const std::int64_t yc = q.cy + dy;
      if (yc < 0 || yc >= dims[1]) continue;
      const double gy = gap_to(q.y, grid.origin[1], yc, grid.cell);
      if (gy * gy + gz * gz > q.reach * q.reach) continue;
      const std::int64_t x0 = std::max<std::int64_t>(q.cx - ext, 0);
      const std::int64_t x1 = std::min<std::int64_t>(q.cx + ext, dims[0] - 1);
      if (x0 > x1) continue;
      const auto base = static_cast<std::size_t>((zc * dims[1] + yc) * dims[0]);
      const std::size_t b = std::max<std::size_t>(grid.start[base + static_cast<std::size_t>(x0)], q.lo);
      const std::size_t e = std::min<std::size_t>(grid.start[base + static_cast<std::size_t>(x1) + 1], q.hi);
      for (std::size_t s0 = b / L * L; s0 < e; s0 += L) {
        const B ddx = B::load_aligned(px + s0) - bx, ddy = B::load_aligned(py + s0) - by,
                ddz = B::load_aligned(pz + s0) - bz;
        const B rs = B::load_aligned(rad + s0);
        const B cut = brs + rs;
        const std::size_t lo = b > s0 ? b - s0 : 0, hi = std::min(L, e - s0);
        std::uint32_t bits = lane_bits(ddx * ddx + ddy * ddy + ddz * ddz < cut * cut && rs <= bkeep) &
                             ((1u << hi) - 1u) & ~((1u << lo) - 1u);
        while (bits != 0) {
          hit(s0 + static_cast<std::size_t>(__builtin_ctz(bits)));
          bits &= bits - 1u;
        }
      }
    }
  }
}

// The query of row i in the grid of all rows (its cell known), on that grid's axes.
Query row_query(const Grains& g, const CellGrid& grid, std::size_t i, double reach, double skin, double keep,
                std::size_t lo, std::size_t hi) {
  const double* const pc[3] = {g.pos.x.data(), g.pos.y.data(), g.pos.z.data()};
  const std::uint32_t c = grid.cell_of[i];
  return {pc[grid.axis[0]][i],
          pc[grid.axis[1]][i],
          pc[grid.axis[2]][i],
          g.radius.r[i],
          static_cast<std::int64_t>(c % grid.dims[0]),
          static_cast<std::int64_t>((c / grid.dims[0]) % grid.dims[1]),
          static_cast<std::int64_t>(c / (grid.dims[0] * grid.dims[1])),
          reach,
          skin,
          keep,
          lo,
          hi};
}

// The columns of the grid of all rows on its axes.
struct AxisColumns {
  const double *x, *y, *z;
  AxisColumns(const Grains& g, const CellGrid& grid) {
    const double* const pc[3] = {g.pos.x.data(), g.pos.y.data(), g.pos.z.data()};
    x = pc[grid.axis[0]];
    y = pc[grid.axis[1]];
    z = pc[grid.axis[2]];
  }
};

}  // namespace

void PairSearch::build_coarse_grid(const Grains& g, double rmax) {
  const std::size_t m = coarse_row_.size();
  std::vector<double> p[3];
  for (auto& v : p) v.resize(m);
  for (std::size_t q = 0; q < m; ++q) {
    p[0][q] = g.pos.x[coarse_row_[q]];
    p[1][q] = g.pos.y[coarse_row_[q]];
    p[2][q] = g.pos.z[coarse_row_[q]];
  }
  // Cells for the largest pair: a coarse query (reach at most 2 r_max + skin) looks one cell around.
  coarse_.build(p[0], p[1], p[2], 2.0 * rmax + skin_, std::size_t(1) << 24, true);
  for (ColumnD* c : {&cx_, &cy_, &cz_, &cr_}) c->resize(m);
  crow_.resize(m);
  for (std::size_t s = 0; s < m; ++s) {
    const std::uint32_t q = coarse_.order[s];
    cx_[s] = p[coarse_.axis[0]][q];
    cy_[s] = p[coarse_.axis[1]][q];
    cz_[s] = p[coarse_.axis[2]][q];
    cr_[s] = g.radius.r[coarse_row_[q]];
    crow_[s] = coarse_row_[q];
  }
}

bool PairSearch::prepare(const Grains& g, const CellGrid& grid, double skin, std::size_t most_pairs) {
  skin_ = skin;
  const std::size_t n = g.n_owned;
  double rmin = n ? g.radius.r[0] : 0.0, rmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    rmin = std::min(rmin, g.radius.r[i]);
    rmax = std::max(rmax, g.radius.r[i]);
  }
  r_max_ = rmax;
  // Fine: radius up to twice the smallest; the fine reach is then at most 3/4 of the largest pair's.
  coarse_row_.clear();
  r_fine_ = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (g.radius.r[i] > 2.0 * rmin) coarse_row_.push_back(static_cast<std::uint32_t>(i));
    else r_fine_ = std::max(r_fine_, g.radius.r[i]);
  }
  extra_start_.assign(n + 1, 0);
  extra_.clear();
  if (coarse_row_.empty()) r_fine_ = rmax;
  else build_coarse_grid(g, rmax);
  // The coarse rows' pairs, then the image rows' (periodic boundaries), in fixed chunks of queries
  // (the result does not depend on the thread count), stopping past most_pairs as the main search does.
  const std::size_t m = coarse_row_.size(), images = g.n - n, queries = m + images;
  if (queries == 0) return true;
  constexpr std::size_t kChunk = 64;
  const std::size_t nchunks = (queries + kChunk - 1) / kChunk;
  chunk_pairs_.resize(nchunks);
  std::atomic<std::size_t> listed{0};
  tbb::parallel_for(std::size_t(0), nchunks, [&](std::size_t k) {
    std::vector<std::uint64_t>& out = chunk_pairs_[k];
    out.clear();
    for (std::size_t q = k * kChunk; q < std::min(queries, (k + 1) * kChunk); ++q) {
      if (listed.load(std::memory_order_relaxed) > most_pairs) return;
      const std::size_t before = out.size();
      if (q < m) coarse_pairs(g, grid, coarse_row_[q], out);
      else image_pairs(g, grid, n + (q - m), out);
      listed.fetch_add(out.size() - before, std::memory_order_relaxed);
    }
  });
  if (listed.load() > most_pairs) return false;
  // By lower row (counting sort, chunks in order: each row's partners in a fixed order).
  for (const auto& v : chunk_pairs_)
    for (std::uint64_t p : v) ++extra_start_[(p >> 32) + 1];
  for (std::size_t i = 0; i < n; ++i) extra_start_[i + 1] += extra_start_[i];
  extra_.resize(extra_start_[n]);
  std::vector<std::uint32_t> fill(extra_start_.begin(), extra_start_.end() - 1);
  for (const auto& v : chunk_pairs_)
    for (std::uint64_t p : v) extra_[fill[p >> 32]++] = static_cast<std::uint32_t>(p);
  return true;
}

void PairSearch::coarse_pairs(const Grains& g, const CellGrid& grid, std::size_t c,
                              std::vector<std::uint64_t>& out) const {
  const auto hi = static_cast<std::uint64_t>(c);
  // Fine rows below c, in the grid of all rows.
  const AxisColumns a(g, grid);
  const double rc = g.radius.r[c];
  const Query fine = row_query(g, grid, c, rc + r_fine_ + skin_, skin_, r_fine_, 0, c);
  scan(grid, a.x, a.y, a.z, g.radius.r.data(), fine, [&](std::size_t j) { out.push_back(std::uint64_t(j) << 32 | hi); });
  // Coarse rows above c, in the coarse grid.
  const CellGrid& cg = coarse_;
  const double p[3] = {g.pos.x[c], g.pos.y[c], g.pos.z[c]};
  Query q{p[cg.axis[0]], p[cg.axis[1]], p[cg.axis[2]], rc, 0, 0, 0, rc + r_max_ + skin_, skin_, r_max_, 0, crow_.size()};
  const auto ext = static_cast<std::int64_t>(std::ceil(q.reach / cg.cell));
  q.cx = cell_index(q.x, cg.origin[0], 1.0 / cg.cell, cg.dims[0], ext);
  q.cy = cell_index(q.y, cg.origin[1], 1.0 / cg.cell, cg.dims[1], ext);
  q.cz = cell_index(q.z, cg.origin[2], 1.0 / cg.cell, cg.dims[2], ext);
  scan(cg, cx_.data(), cy_.data(), cz_.data(), cr_.data(), q, [&](std::size_t s) {
    if (crow_[s] > c) out.push_back(hi << 32 | crow_[s]);
  });
}

void PairSearch::image_pairs(const Grains& g, const CellGrid& grid, std::size_t c,
                             std::vector<std::uint64_t>& out) const {
  // Every owned row within reach of image row c, in the grid of all owned rows (the image lies
  // outside it, past a periodic face: its query cell is clamped as a coarse query's is).
  const AxisColumns a(g, grid);
  const double p[3] = {g.pos.x[c], g.pos.y[c], g.pos.z[c]};
  const double rc = g.radius.r[c];
  Query q{p[grid.axis[0]], p[grid.axis[1]], p[grid.axis[2]], rc, 0, 0, 0, rc + r_max_ + skin_, skin_, r_max_, 0,
          g.n_owned};
  const auto ext = static_cast<std::int64_t>(std::ceil(q.reach / grid.cell));
  q.cx = cell_index(q.x, grid.origin[0], 1.0 / grid.cell, grid.dims[0], ext);
  q.cy = cell_index(q.y, grid.origin[1], 1.0 / grid.cell, grid.dims[1], ext);
  q.cz = cell_index(q.z, grid.origin[2], 1.0 / grid.cell, grid.dims[2], ext);
  const auto hi = static_cast<std::uint64_t>(c);
  scan(grid, a.x, a.y, a.z, g.radius.r.data(), q, [&](std::size_t j) { out.push_back(std::uint64_t(j) << 32 | hi); });
}

void PairSearch::partners(const Grains& g, const CellGrid& grid, std::size_t i,
                          std::vector<std::uint32_t>& out) const {
  // Fine rows above i; with a split, coarse ones are dropped here (the coarse rows' search has them).
  const AxisColumns a(g, grid);
  const Query q = row_query(g, grid, i, g.radius.r[i] + r_fine_ + skin_, skin_, r_fine_, i + 1,
                            std::numeric_limits<std::size_t>::max());
  scan(grid, a.x, a.y, a.z, g.radius.r.data(), q, [&](std::size_t j) { out.push_back(static_cast<std::uint32_t>(j)); });
  out.insert(out.end(), extra_.begin() + extra_start_[i], extra_.begin() + extra_start_[i + 1]);
}

}  // namespace gf
