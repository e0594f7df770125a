// A scene of composite bodies on several ranks (grainflow_mpi run SCENE with [[bodies]]): every rank
// builds and steps the whole scene, and the contacts, 93-98 % of a body step, are shared out among
// the ranks (body_contact_split.hpp: each evaluates every P-th member pair and member against the
// walls, and all ranks then hold every outcome). Every rank sums them in one process's
// order, so the run is bit-identical to `grainflow run` on one process, for any rank count; its
// checkpoints are that program's (checkpoints/checkpoint.gfc), and a run resumes from one on any
// rank count, one process included. Rank 0 writes every output, as `grainflow run` does; the others
// write nothing. The ranks stop after the same step (install_stop_agreement): on a signal, or when
// an output fails on rank 0 (the summary then says "failed" and names the file).
//
// The whole state is on every rank (memory O(bodies) per rank), and the list, the members' placement
// and the integration are done by each: a few per cent of a step, which bounds the speed-up (a
// spatial decomposition of the bodies, as the grains have, would lift both).
#pragma once

#include "app/cli.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/bodies/body_contact_split.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// The split of the ranks of `mpi`: its share sends this rank's outcomes to every other rank.
BodyContactSplit rank_contact_split(const MpiContext& mpi);

// Collective. Returns the exit status as `grainflow run` does (0, 3 when the run failed; a setup
// failure on any rank, such as a checkpoint that cannot be read or a folder that cannot be written,
// is 2 on every rank, rank 0 naming the file).
int run_rank_body_command(const CliOptions& opt, const DemScene& s, const MpiContext& mpi);

}  // namespace gf
