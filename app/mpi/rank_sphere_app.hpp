// A scene of grains on several ranks (grainflow_mpi run SCENE): RankSimulation steps it, each rank
// its box's grains, through the run skeleton (app/run_model.hpp) as every model. Into the output
// folder, as `grainflow run` on one rank: series.csv (rank 0), VTK frames (one .vtp piece per rank, a
// .pvtp per frame and frames.pvd; rank_frames.hpp), pictures, checkpoints (one part per rank and an
// index, rank_checkpoints.hpp), final_state.csv (gathered to rank 0) and summary.json from rank 0,
// with the rank run's own entries: the particle-steps per second of rank 0's grains beside all ranks',
// the decomposition's counters over the main stage (rebuilds, rows migrated, rebalances, ghost rows
// at the end), the final kinetic energy and momentum.
//
// --resume continues a checkpoint's run on as many ranks bit for bit (no settling; series.csv and the
// frames go on from the checkpoint, rows and frames the stopped run wrote after it are replaced); on
// another number of ranks (one included) it continues to round-off, the rows and springs shared out
// to the new boxes (RankSimulation::restore_portable), and the parts it read are left on disk.
// SIGINT/SIGTERM stop the main stage after the same step on every rank. A failure that every rank
// shares (a file that could not be written, a checkpoint that cannot be resumed) ends every rank
// alike; a run that became unphysical on one rank stops them all (MPI_Abort, exit status 3).
#pragma once

#include "app/cli.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// Collective. Returns the exit status: 0, 2 for a checkpoint that cannot be resumed or an output
// folder that cannot be made (rank 0 names the file), 3 for a failed run.
int run_rank_sphere_command(const CliOptions& opt, DemScene scene, const MpiContext& mpi);

}  // namespace gf
