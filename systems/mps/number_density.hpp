// Particle number density n_i = sum_{j != i} W(r_ij) (Zhang kernel), from the current positions. Also refreshes
// each pair's kernel weight, which every other operator of the step reads.
// Reads: FluidNodes x, y, z; NeighborPairs. Writes: FluidNodes n; NeighborPairs w.
#pragma once

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

void compute_number_density(FluidNodes& f, NeighborPairs& nb, double re);

}  // namespace gf
