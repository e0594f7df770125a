// Does the neighbour list still hold every touching pair, though some row moved more than skin/2?
//
// The list holds every pair closer than r_i + r_j + skin at the last rebuild. A pair missing from it
// can touch now only if its rows' displacements d_i, d_j since then add up past the skin, and with D
// the largest displacement that needs d_i > skin - D and d_j > skin - D: both rows are "movers". The
// usual rule (rebuild once D > skin/2) is the case where no pair of movers is ruled out. Here, while
// D < skin and the movers are few, the movers' pairs touching now are found (sort and sweep along
// their widest axis) and looked up in the list: the list is kept unless one is missing. The contacts
// evaluated are the same as with the usual rule, step by step; in a flowing drum, where the fastest
// grains fly over the surface together, it rebuilds about half as often.
//
// The steps are separate functions so that a table split over ranks makes the same check with the
// largest displacement and the movers of every rank (systems/decomposition/mpi/rank_list_cover.hpp).
#pragma once

#include <cstdint>
#include <vector>

#include "engine/grains.hpp"
#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

// A mover as the pair sweep sees it: where it is now, its radius, and what the caller needs to
// find its pair (a row, an id, the rank that owns it).
struct MoverPoint {
  double x = 0, y = 0, z = 0, r = 0;
  std::int64_t id = 0;
  std::uint32_t row = 0;
  int owner = 0;
};

struct ListCover {
  std::vector<std::uint32_t> movers;                // scratch, reused
  std::vector<std::vector<std::uint32_t>> blocks;   // movers per block of rows, reused
  std::vector<MoverPoint> points;                   // the movers as the pair sweep takes them, reused
  std::int64_t kept = 0;              // checks where some row moved past skin/2 and the list was kept
};

// True when every pair of rows touching now (distance below r_i + r_j + reach, with a relative margin
// of 1e-9; reach: the contact law's beyond touching) is in `list`, built at the reference positions
// ref_* with `skin` (pairs within r_i + r_j + reach + skin). False also when the
// movers are too many to check cheaply (more than an eighth of the rows), or D reaches the skin
// (within 1e-9 of it, the margin that keeps the movers' bound safe from round-off).
bool list_covers_contacts(const Grains& g, const double* ref_x, const double* ref_y, const double* ref_z,
                          double skin, const NeighborList& list, ListCover& scratch, double reach = 0.0);

// The steps of that check.

// The largest squared displacement of an owned row from its reference position; NaN when a
// position is not finite (a NaN must reach the rebuild, whose grid build names the row).
double largest_displacement2(const Grains& g, const double* ref_x, const double* ref_y, const double* ref_z);

// The movers' bound: a row is a mover when its displacement exceeds it. Lowered by 1e-9 of the skin,
// far above the round-off of the displacements, so a mover is never dropped by rounding. Zero or
// less (or NaN) when the largest displacement d2max leaves no bound: then the list must be rebuilt.
double mover_bound(double skin, double d2max);

// The owned rows that moved more than `bound` into scratch.movers, in row order, unless they are
// more than `cap`: then false (and scratch.movers holds some of them).
bool collect_movers(const Grains& g, const double* ref_x, const double* ref_y, const double* ref_z, double bound,
                    std::size_t cap, ListCover& scratch);

// Calls touching(a, b) for every pair of `points` closer than r_a + r_b + reach (with the relative
// margin of 1e-9 that counts a pair at the kernel's own bound as touching), until it returns false;
// returns false then, true when every call returned true. Sorts `points` along their widest axis,
// which it turns into x first (the axes are permuted cyclically: distances stay as they were).
template <class Touching>
bool each_touching_pair(std::vector<MoverPoint>& points, double reach, Touching&& touching);

// True when the pair of ids (a, b) is listed under row `owner` (the pair's lower row).
bool listed_under(const NeighborList& list, std::uint32_t owner, std::uint64_t key);

// ---------------------------------------------------------------------------------------------------------------------

// Turns the points' widest axis into x, sorts them along it (ties by id) and returns their largest radius.
double sort_along_widest_axis(std::vector<MoverPoint>& points);

template <class Touching>
bool each_touching_pair(std::vector<MoverPoint>& m, double law_reach, Touching&& touching) {
  // Sorted along x: a touching pair is closer than r_a + r_max there.
  const double rmax = sort_along_widest_axis(m);
  constexpr double kMargin = 1.0 + 1e-9;
  for (std::size_t p = 0; p < m.size(); ++p) {
    const MoverPoint& a = m[p];
    const double along = (a.r + rmax + law_reach) * kMargin;
    for (std::size_t q = p + 1; q < m.size() && m[q].x - a.x < along; ++q) {
      const MoverPoint& b = m[q];
      const double dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
      const double rs = (a.r + b.r + law_reach) * kMargin;
      if (dx * dx + dy * dy + dz * dz < rs * rs && !touching(a, b)) return false;
    }
  }
  return true;
}

}  // namespace gf
