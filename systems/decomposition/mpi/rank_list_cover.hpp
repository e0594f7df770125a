// The list-cover check (systems/broadphase/list_cover.hpp) on a table split over ranks: may every
// rank keep its neighbour list although some row moved past half the skin?
//
// Every rank gives the same answer. The largest displacement D is the largest over all ranks, so the
// movers' bound (d > skin - D) is the same everywhere, and the movers are counted over all ranks (more
// than an eighth of all rows: rebuild). Each rank's movers go to the ranks whose boxes lie within
// `peers` (the boxes within two reaches: a mover is less than a skin from the box it was in at the
// rebuild, and a touching pair spans less than one reach), so every pair of movers touching now is
// seen by the rank that evaluates it, the higher of their owners, which looks it up in its list: under
// the lower row of a pair of its own rows, under its own row for a pair with a lower rank's grain
// (held there as a ghost row). The list is kept unless some rank misses a pair.
#pragma once

#include <vector>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/broadphase/broadphase.hpp"

namespace gf {

// Collective: every rank of mpi's communicator calls it at the same step. `peers`: the ranks whose
// boxes lie within two reaches of this rank's (symmetric). False when the list must be rebuilt.
bool rank_list_covers(const Grains& g, BroadphaseState& s, const NeighborList& list, const MpiContext& mpi,
                      const std::vector<int>& peers);

}  // namespace gf
