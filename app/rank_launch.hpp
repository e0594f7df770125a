// grainflow started by an MPI launcher on several ranks (mpiexec -n P grainflow run SCENE ...): the
// single-process program would run P copies of the scene into one output folder. It hands the ranks
// over to grainflow_mpi, the program built beside it for several ranks: each process replaces itself
// with grainflow_mpi and the same arguments (the launcher's environment kept, so they form one MPI
// job), and a run then steps the scene on P ranks.
#pragma once

#include <optional>
#include <string>

namespace gf {

// The rank count an MPI launcher gave this process (Open MPI's OMPI_COMM_WORLD_SIZE, or PMI_SIZE of
// MPICH's and Slurm's launchers), or none when it was not started by one.
std::optional<int> launched_ranks();

// Replaces this process with grainflow_mpi from the folder of `self` (this program's path) and argv;
// returns only on failure, with the reason.
std::string hand_over_to_ranks(int argc, char** argv);

}  // namespace gf
