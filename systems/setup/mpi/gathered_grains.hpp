// The owned rows of every rank brought to rank 0, for the outputs that need the whole system at
// once: the analyses of a series row that look at all grains together (segregation, Lacey's index,
// the drum's pattern and free surface) and the final state. Only the columns each needs travel.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/fill/state_csv.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// Every rank's grains as one table on rank 0, in id order: position, velocity, radius, species and
// id (no spin columns; masses and forces zero). An empty table on the other ranks. Collective.
Grains gather_shapes(const Grains& g, const MpiContext& mpi);

// Every rank's grains on rank 0 as rows of final_state.csv, in id order: id, type (species from 1),
// the species' diameter, position, velocity and angular velocity (zero for grains that do not
// rotate), as the one-rank run writes them. Empty on the other ranks. Collective.
std::vector<StateRow> gather_state_rows(const Grains& g, const MpiContext& mpi);

}  // namespace gf
