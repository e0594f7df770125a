// Explicit prediction of the semi-implicit step: u* = u + dt (nu <lap u> + g + f_body), r* = r + dt u*, for
// fluid rows. The viscous term uses the MPS Laplacian (kernel.hpp) with wall and dummy nodes at rest (no slip).
// Reads: FluidNodes x, y, z, u, v, w, kind; NeighborPairs (weights at r^n); LiquidParams.
// Writes: FluidNodes u, v, w, x, y, z (fluid rows), ax, ay, az (scratch).
#pragma once

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

void predict_velocity(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt);

// <lap phi>_i for every row into out (size rows), phi read from a column (tests and the viscous term).
void mps_laplacian(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, const ColumnD& phi,
                   ColumnD& out);

}  // namespace gf
