// The seam between the coupling and a liquid solver: what the coupled step (coupled_step.hpp) needs of a
// liquid, so that another solver (a grid, say) is coupled to the grains by a type in its own folder, with no
// edits here. The liquid is a set of carriers (the MPS liquid's: its fluid, wall and dummy nodes, one per
// FluidNodes row); the coupling shares each grain's volume and impulse among the carriers within h of it
// (void_fraction.hpp) and reads the liquid at the grain through the same shares. A liquid type L offers:
//
//   L::SampleReads, L::SampleWrites   what coupling_prepare touches through L (gf::Reads<...>, gf::Writes<...>:
//   L::ReactReads, L::ReactWrites     the liquid's tables and resources), and what liquid_reaction touches;
//                                     they join the systems' own declarations, so the task graph stays exact
//   L(World&)                         a view of the world's liquid, made by each system as it runs
//   carriers()                        how many carriers
//   position(a), velocity(a)          every carrier's coordinate and velocity along axis a (m, m/s)
//   moves(i)                          whether carrier i is free liquid: shares over the moving carriers only
//                                     (coupling.share_with = "fluid_nodes") and the reaction go to these; a
//                                     fixed carrier (a wall) passes its part to the container
//   averaged()                        whether the liquid is locally averaged (coupling.averaged): it then
//   carrier_volumes()                 gives each carrier's volume of mixture (m^3), from which the coupling
//   take_fraction(eps)                makes the liquid fraction, and takes that fraction back as its target
//   add_momentum(i, dp)               adds momentum dp (N s) to moving carrier i
//
// and, once at the start (attach_coupling), its LiquidFacts. The MPS liquid's type is MpsCoupledLiquid
// (systems/mps/mps_coupled_liquid.hpp); tests/coupled_liquid_test.cpp couples a stand-in.
#pragma once

#include <concepts>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/system.hpp"
#include "systems/contact/vec3.hpp"
#include "systems/coupling/drag.hpp"

namespace gf {

// What the coupling keeps of a liquid's settings.
struct LiquidFacts {
  LiquidProps props;          // density and dynamic viscosity, for the drag law and buoyancy
  double carrier_volume = 0;  // m^3, the volume of clear liquid one carrier stands for (MPS: l0^3)
  int periodic_axis = -1;     // 0, 1, 2: the liquid repeats along it, and shares reach across; -1: none
  double period_lo = 0, period_hi = 0;  // m, the period along that axis
};

template <class L>
concept CoupledLiquid = requires(L& l, const L& cl, World& w, std::size_t i, int a, const V3<double>& dp,
                                 std::span<const double> eps) {
  typename L::SampleReads;
  typename L::SampleWrites;
  typename L::ReactReads;
  typename L::ReactWrites;
  L(w);
  { cl.carriers() } -> std::convertible_to<std::size_t>;
  { cl.position(a) } -> std::convertible_to<std::span<const double>>;
  { cl.velocity(a) } -> std::convertible_to<std::span<const double>>;
  { cl.moves(i) } -> std::convertible_to<bool>;
  { cl.averaged() } -> std::convertible_to<bool>;
  { cl.carrier_volumes() } -> std::convertible_to<std::vector<double>>;
  l.take_fraction(eps);
  l.add_momentum(i, dp);
};

// Two access lists as one: Join<gf::Reads<A...>, gf::Reads<B...>>::type is gf::Reads<A..., B...>.
template <class X, class Y>
struct Join;
template <class... A, class... B>
struct Join<Reads<A...>, Reads<B...>> {
  using type = Reads<A..., B...>;
};
template <class... A, class... B>
struct Join<Writes<A...>, Writes<B...>> {
  using type = Writes<A..., B...>;
};

}  // namespace gf
