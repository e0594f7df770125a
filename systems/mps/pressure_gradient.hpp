// Pressure-gradient correction of the semi-implicit step. Seed 003's gradient model
//   <grad p>_i = d/n0 sum_j (p_j + p_i) / r_ij^2 (r_j - r_i) W_ij                  (gradient = "sum", default)
// or Koshizuka & Oka's minimum-pressure form, which only repels and damps clustering noise differently,
//   <grad p>_i = d/n0 sum_j (p_j - p_min,i) / r_ij^2 (r_j - r_i) W_ij,  p_min,i = min(p_i, p_j in range)  ("min").
// Then u' = -dt/rho <grad p>, u = u* + u', r = r* + dt u' on fluid rows.
// Reads: FluidNodes x, y, z, p, kind; NeighborPairs; LiquidParams. Writes: FluidNodes u, v, w, x, y, z, ax, ay, az.
#pragma once

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

// <grad phi>_i of a column into gx, gy, gz for every non-dummy row (tests), in the chosen form.
void mps_gradient(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, GradientForm form,
                  const ColumnD& phi, ColumnD& gx, ColumnD& gy, ColumnD& gz, bool fluid_only = false);

void correct_velocity(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt);

}  // namespace gf
