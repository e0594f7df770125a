// final_state.csv of a run on several ranks: every rank's owned grains gathered to rank 0 and
// written there in the one-rank run's format and order (id order; state_csv.hpp), so that a one-rank
// `grainflow run` can start from it with a `kind = "file"` fill. The portable state of the run.
#pragma once

#include <filesystem>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// Collective; RankFailure on every rank when rank 0 cannot write the file (its message names it).
void write_rank_final_state(const std::filesystem::path& file, const Grains& g, const MpiContext& mpi);

}  // namespace gf
