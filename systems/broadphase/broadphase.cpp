#include "systems/broadphase/broadphase.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace gf {

bool needs_rebuild(const Grains& g, const BroadphaseState& s) {
  if (!s.valid || s.force_rebuild || s.ref_x.size() != g.n) return true;
  const double lim2 = 0.25 * s.skin * s.skin;
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  // Whole batches (the columns are padded with zeros in both tables, which never move), tested a
  // batch at a time; a block stops at its first batch that moved.
  const std::size_t nb = (g.n + L - 1) / L;
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, nb, 512), false,
      [&](const tbb::blocked_range<std::size_t>& r, bool moved) {
        if (moved) return true;
        for (std::size_t b = r.begin(); b != r.end(); ++b) {
          const std::size_t i = b * L;
          const B dx = B::load_aligned(&g.pos.x[i]) - B::load_aligned(&s.ref_x[i]);
          const B dy = B::load_aligned(&g.pos.y[i]) - B::load_aligned(&s.ref_y[i]);
          const B dz = B::load_aligned(&g.pos.z[i]) - B::load_aligned(&s.ref_z[i]);
          // The negated test also catches NaN, which then fails loudly in the grid build.
          if (!xsimd::all(dx * dx + dy * dy + dz * dz <= B(lim2))) return true;
        }
        return false;
      },
      [](bool a, bool b) { return a || b; });
}

namespace {

// Springs of the old list that carry over, found by pair key through an open-addressing table
// (one probe or two per new pair, where a sorted index took ~17 random ones).
struct OldHistory {
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);  // no pair has this key (lo < hi)
  // Key and slot side by side: a probe reads one cache line.
  struct Entry {
    std::uint64_t key;
    std::uint64_t slot;
  };
  std::vector<Entry> table;
  std::uint64_t mask = 0;
  int shift = 64;
  std::array<std::vector<double>, 6> values;

  std::size_t home(std::uint64_t key) const { return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> shift); }
  void build(const std::vector<std::uint64_t>& active_keys) {
    std::size_t cap = 16;
    shift = 60;
    while (cap < 2 * active_keys.size()) {
      cap *= 2;
      --shift;
    }
    mask = cap - 1;
    table.assign(cap, Entry{kEmpty, 0});
    for (std::size_t s = 0; s < active_keys.size(); ++s) {
      std::size_t h = home(active_keys[s]);
      while (table[h].key != kEmpty) h = (h + 1) & mask;
      table[h] = {active_keys[s], s};
    }
  }
  // Slot of the key's springs, or -1.
  std::int64_t find(std::uint64_t key) const {
    for (std::size_t h = home(key);; h = (h + 1) & mask) {
      if (table[h].key == key) return static_cast<std::int64_t>(table[h].slot);
      if (table[h].key == kEmpty) return -1;
    }
  }
  // Asks for the line a find(key) will read first.
  void prefetch(std::uint64_t key) const { __builtin_prefetch(&table[home(key)]); }
};

// The pair law keeps the springs as seen from the owner row i (they change sign with i and j), and
// the owner is the lower row, which re-sorting may make the other particle. So history is carried
// over oriented from the lower id to the higher one, and turned to the new owner's view when placed.
double owner_sign(std::int64_t owner_id, std::int64_t partner_id) { return owner_id < partner_id ? 1.0 : -1.0; }

OldHistory collect_active(const Grains& g, const NeighborList& list, const PairHistory& h) {
  OldHistory old;
  std::vector<std::uint64_t> active;
  active.reserve(h.size());
  for (std::size_t e = 0; e < h.size(); ++e) {
    const auto k = static_cast<std::size_t>(h.pair[e]);
    active.push_back(list.key[k]);
    // Rows are still in the order this list was built for, so i and j name the old owner and partner.
    const double sign = owner_sign(g.pid.id[list.i[k]], g.pid.id[list.j[k]]);
    const double v[6] = {h.sx[e], h.sy[e], h.sz[e], h.rx[e], h.ry[e], h.rz[e]};
    for (int c = 0; c < 6; ++c) old.values[c].push_back(sign * v[c]);
  }
  old.build(active);
  return old;
}

}  // namespace

void rebuild_neighbors(Grains& g, BroadphaseState& s, NeighborList& list, PairHistory& history) {
  OldHistory old = collect_active(g, list, history);
  const std::size_t n = g.n;

  // Cells sized for the smallest pair reach: in a mixture of 1 and 3 mm grains, cells sized for
  // the largest would make a small grain test ~4x more candidates than it can touch. A row then
  // searches as many cells around its own as its own largest reach needs.
  double rmax = 0.0, rmin = n ? g.radius.r[0] : 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    rmax = std::max(rmax, g.radius.r[i]);
    rmin = std::min(rmin, g.radius.r[i]);
  }
  s.grid.build(g.pos.x.span(), g.pos.y.span(), g.pos.z.span(), 2.0 * rmin + s.skin, std::size_t(1) << 24, true);
  CellGrid& grid = s.grid;

  // Cell order, ties by id: the row order becomes a function of positions alone.
  tbb::parallel_for(std::size_t(0), grid.cells(), std::size_t(256), [&](std::size_t c0) {
    const std::size_t c1 = std::min(grid.cells(), c0 + 256);
    for (std::size_t c = c0; c < c1; ++c) {
      auto b = grid.order.begin() + grid.start[c];
      auto e = grid.order.begin() + grid.start[c + 1];
      if (e - b > 1) std::sort(b, e, [&](std::uint32_t a, std::uint32_t bb) { return g.pid.id[a] < g.pid.id[bb]; });
    }
  });
  g.permute(grid.order);
  {
    std::vector<std::uint32_t> sorted_cell(n);
    for (std::size_t r = 0; r < n; ++r) sorted_cell[r] = grid.cell_of[grid.order[r]];
    grid.cell_of.swap(sorted_cell);
    for (std::size_t r = 0; r < n; ++r) grid.order[r] = static_cast<std::uint32_t>(r);
  }

  // Candidate pairs: count per row, prefix, fill. Each row owns pairs with higher rows only.
  const std::size_t nown = g.n_owned;
  list.offsets.assign(nown + 1, 0);
  const auto dims = grid.dims;
  const double skin = s.skin;
  const double cell = grid.cell;
  const double inv_cell = 1.0 / cell;
  const auto origin = grid.origin;
  // Distance from coordinate v to the cell interval [o + k cell, o + (k + 1) cell] along one axis.
  auto gap_to = [&](double v, double o, std::int64_t k) {
    const double lo = o + static_cast<double>(k) * cell;
    return v < lo ? lo - v : std::max(0.0, v - (lo + cell));
  };
  const double* const pc[3] = {g.pos.x.data(), g.pos.y.data(), g.pos.z.data()};
  const double* const rad = g.radius.r.data();
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  auto visit = [&](std::size_t i, auto&& emit) {
    const std::uint32_t c = grid.cell_of[i];
    const std::int64_t cx = c % dims[0];
    const std::int64_t cy = (c / dims[0]) % dims[1];
    const std::int64_t cz = c / (dims[0] * dims[1]);
    // x, y, z here are the grid's axes, which may be any order of the coordinate axes.
    const double* px = pc[grid.axis[0]];
    const double* py = pc[grid.axis[1]];
    const double* pz = pc[grid.axis[2]];
    const double xi = px[i], yi = py[i], zi = pz[i], ri = g.radius.r[i];
    // Only cells that a sphere of the row's largest reach can touch: lines of cells along x (the
    // grid's shortest axis) are culled by their distance in y and z.
    const double reach = ri + rmax + skin;
    const auto ext = static_cast<std::int64_t>(std::ceil(reach * inv_cell));
    for (std::int64_t dz = -ext; dz <= ext; ++dz) {
      const std::int64_t z = cz + dz;
      if (z < 0 || z >= dims[2]) continue;
      const double gz = gap_to(zi, origin[2], z);
      for (std::int64_t dy = -ext; dy <= ext; ++dy) {
        const std::int64_t y = cy + dy;
        if (y < 0 || y >= dims[1]) continue;
        const double gy = gap_to(yi, origin[1], y);
        if (gy * gy + gz * gz > reach * reach) continue;
        // The line is cut to the cells within ext of the row's own; the chord of the sphere would
        // cut it a little shorter, at the cost of a square root and two roundings per line.
        const std::int64_t x0 = std::max<std::int64_t>(cx - ext, 0);
        const std::int64_t x1 = std::min<std::int64_t>(cx + ext, dims[0] - 1);
        // Cells x0..x1 of one (y, z) line are consecutive, so their rows are one range.
        const std::size_t base = static_cast<std::size_t>((z * dims[1] + y) * dims[0]);
        std::size_t b = grid.start[base + x0];
        const std::size_t e = grid.start[base + x1 + 1];
        if (b <= i) b = i + 1;
        // The rows of the line in whole aligned batches (columns are padded to whole batches),
        // lanes outside [b, e) masked off; hits are rare (a few in a hundred), so they are
        // emitted bit by bit.
        for (std::size_t j0 = b / L * L; j0 < e; j0 += L) {
          const B ddx = B::load_aligned(px + j0) - B(xi), ddy = B::load_aligned(py + j0) - B(yi),
                  ddz = B::load_aligned(pz + j0) - B(zi);
          const B cut = (B(ri) + B::load_aligned(rad + j0)) + B(skin);
          const std::size_t lo = b > j0 ? b - j0 : 0, hi = std::min(L, e - j0);
          std::uint32_t bits = lane_bits(ddx * ddx + ddy * ddy + ddz * ddz < cut * cut) &
                               ((1u << hi) - 1u) & ~((1u << lo) - 1u);
          while (bits != 0) {
            emit(j0 + static_cast<std::size_t>(__builtin_ctz(bits)));
            bits &= bits - 1u;
          }
        }
      }
    }
  };
  // One search pass: each fixed block of rows collects its partners, then blocks are laid end to
  // end. Blocks do not depend on the thread count, so neither does the list.
  constexpr std::size_t kRows = 512;
  const std::size_t nblocks = (nown + kRows - 1) / kRows;
  s.partners.resize(nblocks);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    std::vector<std::uint32_t>& out = s.partners[blk];
    out.clear();
    const std::size_t r1 = std::min(nown, (blk + 1) * kRows);
    for (std::size_t i = blk * kRows; i < r1; ++i) {
      const std::size_t before = out.size();
      visit(i, [&](std::size_t j) { out.push_back(static_cast<std::uint32_t>(j)); });
      list.offsets[i + 1] = static_cast<std::uint32_t>(out.size() - before);
    }
  });
  for (std::size_t i = 0; i < nown; ++i) list.offsets[i + 1] += list.offsets[i];
  const std::size_t np = list.offsets[nown];
  list.i.resize(np);
  list.j.resize(np);
  // Padded to whole batches with row 0, a valid index, so kernels may gather past the end.
  list.i_lane.assign(np, 0);
  list.j_lane.assign(np, 0);
  list.type_pair.assign(np, 0);
  list.key.resize(np);
  s.carried.assign(np, -1);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    const std::vector<std::uint32_t>& partners = s.partners[blk];
    const std::size_t r0 = blk * kRows, r1 = std::min(nown, (blk + 1) * kRows);
    std::size_t q = 0;
    for (std::size_t i = r0; i < r1; ++i) {
      const std::int64_t idi = g.pid.id[i];
      for (std::size_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k, ++q) {
        const std::uint32_t j = partners[q];
        list.i[k] = static_cast<std::uint32_t>(i);
        list.j[k] = j;
        list.i_lane[k] = static_cast<std::int32_t>(i);
        list.j_lane[k] = static_cast<std::int32_t>(j);
        list.type_pair[k] = static_cast<std::int32_t>(g.species.type[i] * kMaxSpecies + g.species.type[j]);
        list.key[k] = pair_key(idi, g.pid.id[j]);
      }
    }
    // Old springs by key: the table is read at random, so the probe a few pairs ahead is asked
    // for before this one waits.
    constexpr std::size_t kAhead = 16;
    const std::size_t k0 = list.offsets[r0], k1 = list.offsets[r1];
    for (std::size_t k = k0; k < k1; ++k) {
      if (k + kAhead < k1) old.prefetch(list.key[k + kAhead]);
      s.carried[k] = old.find(list.key[k]);
    }
  });

  // Carried springs in list order, turned to the new owner's view.
  std::size_t carried = 0;
  for (std::size_t k = 0; k < np; ++k) carried += s.carried[k] >= 0;
  history.resize(carried);
  for (std::size_t k = 0, e = 0; k < np; ++k) {
    const std::int64_t slot = s.carried[k];
    if (slot < 0) continue;
    const double sign = owner_sign(g.pid.id[list.i[k]], g.pid.id[list.j[k]]);
    history.pair[e] = static_cast<std::int32_t>(k);
    history.sx[e] = sign * old.values[0][slot];
    history.sy[e] = sign * old.values[1][slot];
    history.sz[e] = sign * old.values[2][slot];
    history.rx[e] = sign * old.values[3][slot];
    history.ry[e] = sign * old.values[4][slot];
    history.rz[e] = sign * old.values[5][slot];
    ++e;
  }
  history.map_slots(np);

  s.ref_x.resize(n);
  s.ref_y.resize(n);
  s.ref_z.resize(n);
  std::copy(g.pos.x.begin(), g.pos.x.end(), s.ref_x.begin());
  std::copy(g.pos.y.begin(), g.pos.y.end(), s.ref_y.begin());
  std::copy(g.pos.z.begin(), g.pos.z.end(), s.ref_z.begin());
  s.valid = true;
  s.force_rebuild = false;
  ++s.rebuilds;
}

void Broadphase::run(World& world) {
  auto& s = world.resources.get<BroadphaseState>();
  ++s.checks;
  if (!needs_rebuild(world.grains, s)) return;
  rebuild_neighbors(world.grains, s, world.resources.get<NeighborList>(), world.resources.get<PairHistory>());
}

}  // namespace gf
