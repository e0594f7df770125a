// Explicit prediction of the semi-implicit step: u* = u + dt ((nu + nu_t) <lap u> + g + f_body), r* = r + dt u*,
// for fluid rows, nu_t the scene's constant eddy viscosity (0 unless set: the crudest turbulence closure, for
// a liquid whose momentum turbulence would mix). The viscous term uses the MPS Laplacian (kernel.hpp) with wall
// and dummy nodes at rest (no slip).
// In a locally averaged liquid (eps per node, liquid_fraction.hpp; empty: eps = 1) the Laplacian is normalised
// by the node's n~0 = eps n0: seed 003's eps mu lap u over the liquid's eps rho is nu lap u per unit mass, and
// the nodes that stand eps n0 apart sum about eps times the full lattice's weights (nu / eps times the n0
// form; on a cubic lattice thinned to eps = 0.7 this reads lap u 10 % high where the n0 form reads it 23 % low).
// Reads: FluidNodes x, y, z, u, v, w, kind; NeighborPairs (weights at r^n); LiquidParams; LiquidFraction.
// Writes: FluidNodes u, v, w, x, y, z (fluid rows), ax, ay, az (scratch).
#pragma once

#include <span>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

// nut: a per-node eddy viscosity (mixing_length.hpp), empty for none.
void predict_velocity(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt,
                      std::span<const double> eps = {}, std::span<const double> nut = {});

// <lap phi>_i for every row into out (size rows), phi read from a column (tests and the viscous term).
void mps_laplacian(const FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k, const ColumnD& phi,
                   ColumnD& out);

}  // namespace gf
