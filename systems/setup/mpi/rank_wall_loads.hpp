// The walls' loads of a run on several ranks (walls.hpp): each rank sums the contacts of the grains
// it owns, so a wall's load is the sum over the ranks, taken on rank 0 in rank order. walls.csv is
// then written by rank 0 as on one rank (rank_series.hpp). A checkpoint holds each rank's own sums in
// its part, and rank 0's part the sums over every rank as well: resumed on as many ranks, each rank
// takes its own back and the run continues bit for bit; on another rank count rank 0 takes the sums
// over the ranks and the others start from zero, which agrees with an uninterrupted run to round-off.
#pragma once

#include "engine/checkpoint_file.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "engine/world.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// The sum over the ranks of every rank's `mine` (its last evaluation and its running sums), on rank
// 0; `mine` itself elsewhere. Collective.
WallLoads gather_wall_loads(const WallLoads& mine, const MpiContext& mpi);

// The analytic walls' and the meshes' sums of this rank in its part, and on rank 0 those over the
// ranks too. Collective.
void save_rank_wall_loads(CheckpointWriter& out, const World& w, const MpiContext& mpi);
// Takes them back from this rank's own part (a run on as many ranks as wrote it).
void restore_rank_wall_loads(const CheckpointReader& in, World& w);
// From part 0 of a checkpoint written on another rank count: rank 0 the sums over the ranks, the
// others zeros.
void restore_rank_wall_loads_portable(const CheckpointReader& first, World& w, const MpiContext& mpi);

}  // namespace gf
