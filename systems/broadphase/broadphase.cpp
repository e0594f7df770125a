#include "systems/broadphase/broadphase.hpp"

#include "engine/machine_memory.hpp"
#include "engine/run_loop.hpp"
#include "engine/simd.hpp"
#include "systems/periodic/periodic_images.hpp"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstdint>
#include <array>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

namespace gf {

bool list_invalid(const Grains& g, const BroadphaseState& s) {
  return !s.valid || s.force_rebuild || s.ref_x.size() != g.n || !g.pending.empty();
}

bool needs_rebuild(const Grains& g, const BroadphaseState& s) {
  if (list_invalid(g, s)) return true;
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

// The history of the old list, each entry with the rows of its pair before re-sorting (i the
// owner, whose view the history is in). Rows move by a permutation, so after re-sorting a spring's pair
// is found at its rows' new places, among the new owner's partners: no search by key.
struct OldHistory {
  std::vector<std::uint32_t> i, j;
  std::array<std::vector<double>, kMaxHistory> values;  // the law's width of them
};

OldHistory collect_active(const Grains& g, const PeriodicImages& im, const NeighborList& list, const PairHistory& h) {
  OldHistory old;
  const std::size_t m = h.size();
  old.i.resize(m);
  old.j.resize(m);
  const std::size_t w = h.width;
  for (std::size_t c = 0; c < w; ++c) old.values[c].resize(m);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e) {
      const auto k = static_cast<std::size_t>(h.pair[e]);
      old.i[e] = list.i[k];
      old.j[e] = base_row(g, im, list.j[k]);  // an image's spring is its owner's
      for (std::size_t c = 0; c < w; ++c) old.values[c][e] = h.value[c][e];
    }
  });
  return old;
}

// Applies the table's queued inserts and removals, then renames the old springs' rows to the
// rows after it; springs of a removed grain are dropped, every other keeps its values.
void apply_row_changes(Grains& g, OldHistory& old) {
  const std::vector<std::int64_t> new_row = g.apply_pending();
  std::size_t e = 0;
  for (std::size_t f = 0; f < old.i.size(); ++f) {
    const std::int64_t a = new_row[old.i[f]], b = new_row[old.j[f]];
    if (a < 0 || b < 0) continue;
    old.i[e] = static_cast<std::uint32_t>(a);
    old.j[e] = static_cast<std::uint32_t>(b);
    for (auto& v : old.values) if (!v.empty()) v[e] = v[f];
    ++e;
  }
  old.i.resize(e);
  old.j.resize(e);
  for (auto& v : old.values) if (!v.empty()) v.resize(e);
}

// The list index of the pair of owned rows a < b: (a, b), or with periodic images (a, image of b)
// or (b, image of a); -1 when the pair is not listed.
std::int64_t listed_pair(const Grains& g, const PeriodicImages& im, const NeighborList& list, std::uint32_t a,
                         std::uint32_t b) {
  for (std::size_t k = list.offsets[a]; k < list.offsets[a + 1]; ++k)
    if (base_row(g, im, list.j[k]) == b) return static_cast<std::int64_t>(k);
  if (im.size() == 0) return -1;
  for (std::size_t k = list.offsets[b]; k < list.offsets[b + 1]; ++k)
    if (list.j[k] >= g.n_owned && base_row(g, im, list.j[k]) == a) return static_cast<std::int64_t>(k);
  return -1;
}

}  // namespace

void rebuild_neighbors(Grains& g, BroadphaseState& s, NeighborList& list, PairHistory& history) {
  PeriodicImages none;
  rebuild_neighbors(g, s, list, history, none);
}

void rebuild_neighbors(Grains& g, BroadphaseState& s, NeighborList& list, PairHistory& history, PeriodicImages& im) {
  rebuild_neighbors(g, s, list, history, im, GhostRowMaker{});
}

void rebuild_neighbors(Grains& g, BroadphaseState& s, NeighborList& list, PairHistory& history, PeriodicImages& im,
                       const GhostRowMaker& add_ghosts) {
  if (add_ghosts && (im.box.any() || history.size() != 0))
    throw std::logic_error("rebuild_neighbors: ghost rows from elsewhere need no periodic faces and an empty history");
  // Ghost rows other than periodic images would be another domain's, which this search does not place.
  if (g.n - g.n_owned != im.size())
    throw std::logic_error("rebuild_neighbors: the table has ghost rows, which the neighbour search does not place");
  OldHistory old = collect_active(g, im, list, history);
  g.set_ghosts(0);
  if (!g.pending.empty()) apply_row_changes(g, old);
  if (im.box.any()) wrap_positions(g, im.box);
  const std::size_t n = g.n;

  // Cells sized for the smallest pair reach: in a mixture of 1 and 3 mm grains, cells sized for
  // the largest would make a small grain test ~4x more candidates than it can touch (the search by
  // size class, PairSearch, finds the large partners in a coarser grid of their own).
  double rmin = n ? g.radius.r[0] : 0.0;
  for (std::size_t i = 0; i < n; ++i) rmin = std::min(rmin, g.radius.r[i]);
  // A law acting before touching (reach > 0) interacts out to r_i + r_j + reach: the search takes
  // reach + skin where the others take the skin.
  const double search = s.skin + s.reach;
  s.grid.build(g.pos.x.span(), g.pos.y.span(), g.pos.z.span(), 2.0 * rmin + search, std::size_t(1) << 24, true);
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
  // New place of each old row (grid.order maps new places to old rows), then the grid in new rows.
  s.new_row.resize(n);
  {
    std::vector<std::uint32_t> sorted_cell(n);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t q = r.begin(); q != r.end(); ++q) {
        s.new_row[grid.order[q]] = static_cast<std::uint32_t>(q);
        sorted_cell[q] = grid.cell_of[grid.order[q]];
      }
    });
    grid.cell_of.swap(sorted_cell);
    for (std::size_t r = 0; r < n; ++r) grid.order[r] = static_cast<std::uint32_t>(r);
  }
  // Periodic images of the sorted rows, within the reach of the largest pair past the faces.
  double rmax = 0.0;
  for (std::size_t i = 0; i < n; ++i) rmax = std::max(rmax, g.radius.r[i]);
  make_images(g, im, 2.0 * rmax + search);
  if (add_ghosts) add_ghosts(g);

  // Candidate pairs: count per row, prefix, fill. Each row owns pairs with higher rows only.
  const std::size_t nown = g.n_owned;
  list.offsets.assign(nown + 1, 0);
  // One search pass: each fixed block of rows collects its partners, then blocks are laid end to
  // end. Blocks do not depend on the thread count, so neither does the list.
  constexpr std::size_t kRows = 512;
  const std::size_t nblocks = (nown + kRows - 1) / kRows;
  s.partners.resize(nblocks);
  // Grains piled far closer than any packing (a corrupt state, a blow-up) would list up to n^2 / 2
  // pairs: the search stops once the list would take half the memory (kBytesPerPair with its
  // contact and history), and the step stops with the reason instead of exhausting the machine.
  constexpr std::size_t kBytesPerPair = 64;
  const std::size_t most_pairs = std::min<std::size_t>(half_of_memory() / kBytesPerPair, UINT32_MAX);
  auto too_many = [&] {
    list.offsets.assign(nown + 1, 0);
    return StabilityError("the neighbour list passed " + std::to_string(most_pairs) + " pairs (" +
                          std::to_string(most_pairs / std::max<std::size_t>(nown, 1)) +
                          " per grain), half of this machine's memory: grains are piled far closer than a "
                          "packing. Fix: a state file's positions, or reduce run.dt if the run blew up");
  };
  if (!s.search.prepare(g, grid, search, most_pairs)) throw too_many();
  std::atomic<std::size_t> listed{0};
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t blk) {
    std::vector<std::uint32_t>& out = s.partners[blk];
    out.clear();
    const std::size_t r1 = std::min(nown, (blk + 1) * kRows);
    for (std::size_t i = blk * kRows; i < r1 && listed.load(std::memory_order_relaxed) <= most_pairs; ++i) {
      const std::size_t before = out.size();
      s.search.partners(g, grid, i, out);
      list.offsets[i + 1] = static_cast<std::uint32_t>(out.size() - before);
      listed.fetch_add(out.size() - before, std::memory_order_relaxed);
    }
  });
  if (listed.load() > most_pairs) throw too_many();
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
  });

  // Each old spring to its pair's new list index: its rows' new places, the lower one the owner,
  // the other among the owner's partners (a pair that left the list drops its spring). Pairs are
  // distinct, so every spring writes its own entry.
  // With periodic images the pair may now be listed as (a, image of b) or (b, image of a): the
  // partners of both are searched for the other's row or image.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, old.i.size(), 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t e = r.begin(); e != r.end(); ++e) {
      const std::uint32_t a = s.new_row[old.i[e]], b = s.new_row[old.j[e]];
      const std::uint32_t own = std::min(a, b), other = std::max(a, b);
      if (own >= nown) continue;
      const std::int64_t k = listed_pair(g, im, list, own, other);
      if (k >= 0) s.carried[static_cast<std::size_t>(k)] = static_cast<std::int64_t>(e);
    }
  });

  // Carried history in list order, turned to the new owner's view (the law keeps them as seen from
  // the owner row, and re-sorting may have made the other grain the owner), and their slot map.
  // Blocks of pairs count, then fill from their running sum.
  constexpr std::size_t kPairs = 8192;
  const std::size_t npb = (np + kPairs - 1) / kPairs;
  std::vector<std::size_t> base(npb + 1, 0);
  tbb::parallel_for(std::size_t(0), npb, [&](std::size_t b) {
    std::size_t c = 0;
    for (std::size_t k = b * kPairs; k < std::min(np, (b + 1) * kPairs); ++k) c += s.carried[k] >= 0;
    base[b + 1] = c;
  });
  for (std::size_t b = 0; b < npb; ++b) base[b + 1] += base[b];
  history.resize(base[npb]);
  history.slot.assign(np, -1);
  const std::size_t width = history.width;
  tbb::parallel_for(std::size_t(0), npb, [&](std::size_t b) {
    std::size_t e = base[b];
    for (std::size_t k = b * kPairs; k < std::min(np, (b + 1) * kPairs); ++k) {
      const std::int64_t from = s.carried[k];
      if (from < 0) continue;
      const auto f = static_cast<std::size_t>(from);
      const double sign = list.i[k] == s.new_row[old.i[f]] ? 1.0 : history.exchange_sign;  // owner view
      history.pair[e] = static_cast<std::int32_t>(k);
      history.slot[k] = static_cast<std::int32_t>(e);
      for (std::size_t c = 0; c < width; ++c) history.value[c][e] = sign * old.values[c][f];
      ++e;
    }
  });

  s.ref_x.resize(g.n);
  s.ref_y.resize(g.n);
  s.ref_z.resize(g.n);
  std::copy(g.pos.x.begin(), g.pos.x.end(), s.ref_x.begin());
  std::copy(g.pos.y.begin(), g.pos.y.end(), s.ref_y.begin());
  std::copy(g.pos.z.begin(), g.pos.z.end(), s.ref_z.begin());
  s.valid = true;
  s.force_rebuild = false;
  ++s.rebuilds;
}

void Broadphase::run(World& world, const StepContext&) {
  auto& s = world.resources.get<BroadphaseState>();
  ++s.checks;
  Grains& g = world.grains;
  if (!needs_rebuild(g, s)) return;
  NeighborList& list = world.resources.get<NeighborList>();
  // A world without the resource has no periodic faces.
  PeriodicImages* im = world.resources.find<PeriodicImages>();
  const bool periodic = im && im->box.any();
  // The check that keeps the list sweeps owned rows only: with periodic images it is not made.
  if (!list_invalid(g, s) && !periodic &&
      list_covers_contacts(g, s.ref_x.data(), s.ref_y.data(), s.ref_z.data(), s.skin, list, s.cover, s.reach)) {
    ++s.cover.kept;
    return;
  }
  if (im) rebuild_neighbors(g, s, list, world.resources.get<PairHistory>(), *im);
  else rebuild_neighbors(g, s, list, world.resources.get<PairHistory>());
}

}  // namespace gf
