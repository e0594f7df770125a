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
#pragma once

#include <cstdint>
#include <vector>

#include "engine/grains.hpp"
#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

struct ListCover {
  std::vector<std::uint32_t> movers;                // scratch, reused
  std::vector<std::vector<std::uint32_t>> blocks;   // movers per block of rows, reused
  std::int64_t kept = 0;              // checks where some row moved past skin/2 and the list was kept
};

// True when every pair of rows touching now (distance below r_i + r_j + reach, with a relative margin
// of 1e-9; reach: the contact law's beyond touching) is in `list`, built at the reference positions
// ref_* with `skin` (pairs within r_i + r_j + reach + skin). False also when the
// movers are too many to check cheaply (more than an eighth of the rows), or D reaches the skin
// (within 1e-9 of it, the margin that keeps the movers' bound safe from round-off).
bool list_covers_contacts(const Grains& g, const double* ref_x, const double* ref_y, const double* ref_z,
                          double skin, const NeighborList& list, ListCover& scratch, double reach = 0.0);

}  // namespace gf
