// Row migration between ranks: the owned rows a rank no longer owns go, whole, to their new owner.
//
// Every column moves (row_bytes.hpp: the core columns, spins when present, and every attached
// column such as the wall springs and mesh slots), so a row arrives byte-identical and keeps its id.
// Each rank keeps its remaining rows in their order and appends the arrivals after them, by sending
// rank, in the sender's row order: the result depends on the positions alone. Ghost rows are
// dropped (the ghost exchange refills them). Called at a neighbour rebuild, where rows may move.
// The pair springs (PairHistory) are not rows: migrate_rows leaves them, and RankSimulation
// (rank_simulation.hpp) sends each to the rank that evaluates its pair next, by pair key.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/decomposition/rcb.hpp"

namespace gf {

struct MigrationCount {
  std::size_t sent = 0, received = 0;  // rows
};

// The rank that owns each owned row's centre.
std::vector<int> row_owners(const Grains& g, const Rcb& rcb);

// Sends every owned row whose owner[row] is another rank there and appends the rows other ranks
// send here. owner holds one rank per owned row. With `peers` (see MpiContext::exchange) the rows
// may only go to those ranks, and only they are exchanged with; without, every rank.
MigrationCount migrate_rows(Grains& g, std::span<const int> owner, const MpiContext& mpi,
                            const std::vector<int>* peers = nullptr);

}  // namespace gf
