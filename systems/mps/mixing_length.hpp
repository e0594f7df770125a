// A turbulent pipe's eddy viscosity per node (the liquid's `turbulence = "mixing_length"`, pipe geometry only):
//   nu_t,i = l_m(y_i)^2 |S_i|,   |S| = sqrt(2 S:S),   S = (G + G^T) / 2
//   l_m / R = 0.14 - 0.08 (1 - y/R)^2 - 0.06 (1 - y/R)^4       (Nikuradse; about 0.41 y near the wall)
// with y = R - r the node's distance from the wall and G its velocity gradient by the MPS gradient model,
// G_ab = d/n0 sum_j (u_b,j - u_b,i) (x_a,j - x_a,i) / r_ij^2 W_ij over its neighbours (wall and dummy nodes at
// rest). Wall and dummy nodes get nu_t = 0. The momentum diffusion (explicit_step.hpp) then uses, pair by pair,
// nu + eddy_viscosity + nu_t,ij with nu_t,ij the mean of the two nodes' where both are fluid and the fluid
// node's against a wall node. No van Driest damping: at this model's resolution (l0 of several mm) the first
// nodes lie in the log layer (y+ in the hundreds), where l_m = 0.41 y holds.
#pragma once

#include <vector>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

// Nikuradse's mixing length over the radius at wall distance y / R (clamped to [0, 1]).
double nikuradse_length(double y_over_r);

// The eddy viscosity (m^2/s) of every node from the nodes' current velocities, into nut (resized).
void mixing_length_viscosity(const FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp,
                             std::vector<double>& nut);

// Where the liquid keeps it between the two passes of a step (a world resource while the model is on).
struct EddyViscosity {
  std::vector<double> nut;  // m^2/s, per node
};

}  // namespace gf
