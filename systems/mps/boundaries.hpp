// Boundary geometry of the liquid, turned into wall and dummy particle layers on the fluid's lattice (spacing
// l0, nodes at cell centres, so every wall face lies half a spacing from the nearest fluid and wall nodes):
//   box     closed rectangular box (all faces walled);
//   tank    box open at the top (+y): gravity points along -y;
//   channel box periodic along x: walls only on the y (and, in 3D, z) faces; flow driven by a body force;
//   pipe    3D circular pipe along x, periodic along x, of radius R around `center`.
// The first layer outside the fluid region holds wall nodes (pressure solved), the next ones dummy nodes
// (pressure extrapolated), as many as the kernel radius reaches (layers >= ceil(re/l0)).
#pragma once

#include <array>
#include <vector>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

struct LiquidGeometry {
  enum class Kind { Box, Tank, Channel, Pipe };
  Kind kind = Kind::Tank;
  int dim = 2;
  std::array<double, 3> lo{}, hi{};  // m, inner faces (pipe: lo.x, hi.x axial ends, y/z unused)
  std::array<double, 3> center{};    // m, pipe axis passes through (., center.y, center.z)
  double radius = 0;                 // m, pipe inner radius
  int layers = 3;                    // wall + dummy layers

  Periodicity periodicity() const;
  // True if the point (m) is inside the fluid region (the box's interior, the pipe's bore).
  bool interior(double x, double y, double z) const;
  // Outer bounding box of every node the geometry generates (m).
  void bounds(double l0, std::array<double, 3>& lo_out, std::array<double, 3>& hi_out) const;
};

struct FluidBlock {
  std::array<double, 3> lo{}, hi{};  // m; lattice nodes inside [lo, hi) and inside the geometry become fluid
  std::array<double, 3> velocity{};  // m/s, the block's nodes' starting velocity
};

// Appends fluid nodes (first, at their block's velocity), then wall and dummy nodes (at rest), all with p = 0.
void generate_nodes(const LiquidGeometry& g, const std::vector<FluidBlock>& blocks, double l0, FluidNodes& f);

// Dummy pressure from its wall neighbours, hydrostatically corrected:
//   p_d = sum_w W_dw (p_w + rho a.(r_d - r_w)) / sum_w W_dw,  a = gravity + body force,
// 0 for a dummy node with no wall node in range.
void extrapolate_dummy_pressure(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp);

}  // namespace gf
