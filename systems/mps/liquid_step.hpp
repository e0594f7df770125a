// The semi-implicit MPS step as a schedule of systems, in phase order (seed 003 / Koshizuka & Oka):
//   neighbour_search   when a node moved > skin/2: wrap periodic positions, rebuild the list (radius re + skin)
//   number_density     kernel weights and n at r^n (weights for the viscous Laplacian)
//   explicit_step      u* = u + dt (nu lap u + g + f), r* = r + dt u*
//   predicted_density  weights and n* at r*; density-spike check
//   free_surface       surface nodes (n* < beta n0) get p = 0
//   pressure_solve     PPE with the mixed source, solver check
//   dummy_pressure     extrapolate dummy pressures from wall nodes
//   pressure_correct   u = u* - dt/rho grad p, r = r* + dt u'
//   collision          Koshizuka-Oka collision model (liquid.collision_distance, 0 = off)
//   motion_check       CFL, escaped or non-finite particles
// Every system reads and writes the whole FluidNodes table and whole resources (NeighborPairs ...), so the graph is the
// chain above; each system's own loops run in parallel.
#pragma once

#include "engine/schedule.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/stability.hpp"

namespace gf {

// With `drive`, drive_control (flow_drive.hpp) comes first: the body force for this step.
void schedule_liquid_step(Schedule& step, bool drive = false);

}  // namespace gf
