// The MPS liquid as the coupling sees it (the seam: systems/coupling/coupled_liquid.hpp). Its carriers are
// the FluidNodes rows: fluid nodes move and take the grains' reaction; wall and dummy nodes stand still and
// pass theirs on to the tank. A node's clear-liquid volume is l0^3 and its mass rho l0^3. Locally averaged
// (coupling.averaged: the LiquidFraction resource), a node stands for its own volume of mixture
// (mixture_volumes) and the liquid fraction the coupling makes of it becomes the PPE's target eps n0.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "engine/system.hpp"
#include "engine/world.hpp"
#include "systems/contact/vec3.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_fraction.hpp"
#include "systems/mps/liquid_params.hpp"

namespace gf {

// The volume of mixture each node stands for in a locally averaged liquid, whose nodes thin out to
// n = eps n0 where grains are: V_i = l0^dim n0 / n_i (l0^dim where the nodes sit at n0). With the
// fixed l0^dim instead, a node of a thinned bed would hold its grains' share in too small a volume and
// read eps too low (1 - phi / (n / n0) for a solid fraction phi), and the lower target would thin the
// nodes further. n_i below n0 / 2 (a node at a free surface, whose kernel is cut, not thinned) counts as
// n0 / 2; n_i = 0 (not computed yet) as n0.
std::vector<double> mixture_volumes(std::span<const double> n, double n0, double node_volume);

class MpsCoupledLiquid {
 public:
  // coupling_prepare reads the nodes (positions, kinds, velocities; averaged, the number density and
  // LiquidParams' n0 and l0) and, averaged, writes the liquid fraction; liquid_reaction reads rho and l0
  // (a node's mass) and writes the fluid nodes' velocities.
  using SampleReads = Reads<FluidNodes, LiquidParams>;
  using SampleWrites = Writes<LiquidFraction>;
  using ReactReads = Reads<LiquidParams>;
  using ReactWrites = Writes<FluidNodes>;

  explicit MpsCoupledLiquid(World& w);

  std::size_t carriers() const { return f_.size(); }
  std::span<const double> position(int axis) const { return column(axis == 0 ? f_.x : axis == 1 ? f_.y : f_.z); }
  std::span<const double> velocity(int axis) const { return column(axis == 0 ? f_.u : axis == 1 ? f_.v : f_.w); }
  bool moves(std::size_t i) const { return f_.kind[i] == kFluid; }
  bool averaged() const { return fraction_ != nullptr; }
  std::vector<double> carrier_volumes() const;
  void take_fraction(std::span<const double> eps) { fraction_->eps.assign(eps.begin(), eps.end()); }
  void add_momentum(std::size_t i, const V3<double>& dp) {
    f_.u[i] += dp.x / mass_;
    f_.v[i] += dp.y / mass_;
    f_.w[i] += dp.z / mass_;
  }

 private:
  std::span<const double> column(const ColumnD& c) const { return {c.data(), f_.size()}; }

  FluidNodes& f_;
  const LiquidParams& params_;
  LiquidFraction* fraction_;
  double volume_;  // m^3, l0^3
  double mass_;    // kg, rho l0^3
};

}  // namespace gf
