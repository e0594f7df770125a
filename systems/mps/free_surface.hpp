// Free-surface detection (Koshizuka & Oka 1996): a fluid or wall node whose number density n* after the
// prediction is below beta n0 lies on the free surface and gets the Dirichlet condition p = 0 in the PPE.
// Dummy nodes are never in the PPE. A closed liquid (liquid.free_surface = false: a full periodic pipe or
// channel) has none: a node the grains' reaction or the flow thins below beta n0 inside it would be held
// at p = 0 as if it bordered air (in the transport pipe such runs failed; see its scene).
// In a locally averaged liquid the test is n* < beta eps n0 with the node's liquid fraction eps
// (liquid_fraction.hpp; empty: eps = 1).
// Reads: FluidNodes n, kind; LiquidParams beta, n0. Writes: FluidNodes surface. Returns the surface count.
#pragma once

#include <cstddef>
#include <span>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"

namespace gf {

std::size_t detect_free_surface(FluidNodes& f, const LiquidParams& lp, std::span<const double> eps = {});

}  // namespace gf
