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
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, g.n, 4096), false,
      [&](const tbb::blocked_range<std::size_t>& r, bool moved) {
        if (moved) return true;
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const double dx = g.pos.x[i] - s.ref_x[i];
          const double dy = g.pos.y[i] - s.ref_y[i];
          const double dz = g.pos.z[i] - s.ref_z[i];
          // The negated test also catches NaN, which then fails loudly in the grid build.
          if (!(dx * dx + dy * dy + dz * dz <= lim2)) return true;
        }
        return false;
      },
      [](bool a, bool b) { return a || b; });
}

namespace {

struct OldHistory {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> index;  // (key, slot) sorted by key
  std::array<std::vector<double>, 6> values;
};

// The pair law keeps the springs as seen from the owner row i (they change sign with i and j), and
// the owner is the lower row, which re-sorting may make the other particle. So history is carried
// over oriented from the lower id to the higher one, and turned to the new owner's view when placed.
double owner_sign(std::int64_t owner_id, std::int64_t partner_id) { return owner_id < partner_id ? 1.0 : -1.0; }

OldHistory collect_active(const Grains& g, const NeighborList& list, PairHistory& h) {
  OldHistory old;
  const std::size_t np = list.pairs();
  for (std::size_t k = 0; k < np; ++k) {
    if (h.sx[k] != 0.0 || h.sy[k] != 0.0 || h.sz[k] != 0.0 || h.rx[k] != 0.0 || h.ry[k] != 0.0 || h.rz[k] != 0.0) {
      const auto slot = static_cast<std::uint32_t>(old.index.size());
      old.index.emplace_back(list.key[k], slot);
      // Rows are still in the order this list was built for, so i and j name the old owner and partner.
      const double sign = owner_sign(g.pid.id[list.i[k]], g.pid.id[list.j[k]]);
      std::size_t c = 0;
      for_each_column(h, [&](ColumnD& col) { old.values[c++].push_back(sign * col[k]); });
    }
  }
  tbb::parallel_sort(old.index.begin(), old.index.end());
  return old;
}

}  // namespace

void rebuild_neighbors(Grains& g, BroadphaseState& s, NeighborList& list, PairHistory& history) {
  OldHistory old = collect_active(g, list, history);
  const std::size_t n = g.n;

  double rmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, g.radius.r[i]);
  const double reach = 2.0 * rmax + s.skin;
  s.grid.build(g.pos.x.span(), g.pos.y.span(), g.pos.z.span(), reach);
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
  auto visit = [&](std::size_t i, auto&& emit) {
    const std::uint32_t c = grid.cell_of[i];
    const std::int64_t cx = c % dims[0];
    const std::int64_t cy = (c / dims[0]) % dims[1];
    const std::int64_t cz = c / (dims[0] * dims[1]);
    const double xi = g.pos.x[i], yi = g.pos.y[i], zi = g.pos.z[i], ri = g.radius.r[i];
    for (std::int64_t dz = -1; dz <= 1; ++dz) {
      const std::int64_t z = cz + dz;
      if (z < 0 || z >= dims[2]) continue;
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const std::int64_t y = cy + dy;
        if (y < 0 || y >= dims[1]) continue;
        const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0);
        const std::int64_t x1 = std::min<std::int64_t>(cx + 1, dims[0] - 1);
        // Cells x0..x1 of one (y, z) line are consecutive, so their rows are one range.
        const std::size_t base = static_cast<std::size_t>((z * dims[1] + y) * dims[0]);
        std::size_t b = grid.start[base + x0];
        const std::size_t e = grid.start[base + x1 + 1];
        if (b <= i) b = i + 1;
        for (std::size_t j = b; j < e; ++j) {
          const double ddx = g.pos.x[j] - xi, ddy = g.pos.y[j] - yi, ddz = g.pos.z[j] - zi;
          const double cut = ri + g.radius.r[j] + skin;
          if (ddx * ddx + ddy * ddy + ddz * ddz < cut * cut) emit(j);
        }
      }
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nown, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::uint32_t count = 0;
      visit(i, [&](std::size_t) { ++count; });
      list.offsets[i + 1] = count;
    }
  });
  for (std::size_t i = 0; i < nown; ++i) list.offsets[i + 1] += list.offsets[i];
  const std::size_t np = list.offsets[nown];
  list.i.resize(np);
  list.j.resize(np);
  list.key.resize(np);
  for_each_column(history, [np](ColumnD& col) { col.assign(np, 0.0); });
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nown, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      std::size_t k = list.offsets[i];
      const std::int64_t idi = g.pid.id[i];
      visit(i, [&](std::size_t j) {
        list.i[k] = static_cast<std::uint32_t>(i);
        list.j[k] = static_cast<std::uint32_t>(j);
        const std::uint64_t key = pair_key(idi, g.pid.id[j]);
        list.key[k] = key;
        auto it = std::lower_bound(old.index.begin(), old.index.end(), std::make_pair(key, std::uint32_t(0)));
        if (it != old.index.end() && it->first == key) {
          const std::uint32_t slot = it->second;
          const double sign = owner_sign(idi, g.pid.id[j]);
          history.sx[k] = sign * old.values[0][slot];
          history.sy[k] = sign * old.values[1][slot];
          history.sz[k] = sign * old.values[2][slot];
          history.rx[k] = sign * old.values[3][slot];
          history.ry[k] = sign * old.values[4][slot];
          history.rz[k] = sign * old.values[5][slot];
        }
        ++k;
      });
    }
  });

  // Transposed incidence in pair order: deterministic per-row force sums.
  list.in_offsets.assign(n + 1, 0);
  for (std::size_t k = 0; k < np; ++k) ++list.in_offsets[list.j[k] + 1];
  for (std::size_t r = 0; r < n; ++r) list.in_offsets[r + 1] += list.in_offsets[r];
  list.in_pairs.resize(np);
  {
    std::vector<std::uint32_t> fill(list.in_offsets.begin(), list.in_offsets.end() - 1);
    for (std::size_t k = 0; k < np; ++k) list.in_pairs[fill[list.j[k]]++] = static_cast<std::uint32_t>(k);
  }

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
