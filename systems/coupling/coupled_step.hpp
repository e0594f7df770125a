// The liquid and the grains in one step (seed 003's multi-rate coupling). The liquid's step is the outer
// schedule; the DEM step runs k times inside it at dt/k as one of its systems (engine/sub_schedule.hpp):
//   coupling_prepare   shares of every grain on the nodes within h (void_fraction.hpp), the nodes' liquid
//                      fraction eps_i, and the liquid's velocity and fraction read at each grain
//   dem_substeps       k DEM steps (with coupling.fixed_grains only liquid_force, the grains staying put);
//                      in each, liquid_force sets F = F_d/eps - V_p rho_l g (+ lift: lift.hpp) on every grain
//                      (drag.hpp: the scene's drag law with the grain's own velocity, the liquid's read at
//                      the step's start; buoyancy in Archimedes' form) and adds the impulse the
//                      integrator's two half-kicks give it, h/2 (F_old + F_new), to the grain's tally
//   liquid_reaction    minus each grain's tally, shared with the same weights, changes the nodes'
//                      momentum: du_i = -(1/(rho V_i)) sum_p w_ip J_p, V_i = l0^3; fixed wall and dummy
//                      nodes pass their share to the tank. Grain impulse plus liquid reaction is zero to
//                      rounding (CouplingState's totals; tests/coupled_step_test.cpp)
//   the liquid's step  (liquid_step.hpp), from the kicked velocities
// The liquid is read and kicked through the seam of coupled_liquid.hpp: the systems that touch it take the
// liquid's type L (the MPS liquid's: MpsCoupledLiquid, systems/mps/mps_coupled_liquid.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "engine/column.hpp"
#include "engine/grains.hpp"
#include "engine/schedule.hpp"
#include "engine/sub_schedule.hpp"
#include "systems/coupling/coupled_liquid.hpp"
#include "systems/coupling/coupling_settings.hpp"
#include "systems/coupling/drag.hpp"
#include "systems/coupling/lift.hpp"
#include "systems/coupling/rotational_drag.hpp"
#include "systems/coupling/void_fraction.hpp"
#include "systems/integrate/force_terms.hpp"

namespace gf {

// The liquid's force on each grain (N), a force term of the DEM integrator.
struct LiquidForce {
  ColumnD x, y, z;
  auto columns() { return std::tie(x, y, z); }
};
// Read at each grain at the outer step's start: the liquid's velocity (m/s) and fraction, and the
// grain's row in that step's shares (rows may be re-sorted during the sub-steps).
struct LiquidAtGrain {
  ColumnD ux, uy, uz, eps;
  ColumnD curl_x, curl_y, curl_z;  // 1/s, the liquid's curl (with rotational drag or lift; zero without)
  Column<std::int32_t> row;
  auto columns() { return std::tie(ux, uy, uz, eps, curl_x, curl_y, curl_z, row); }
};
// The liquid's torque on each grain (N m): rotational drag (rotational_drag.hpp), with [coupling]
// rotational_drag only.
struct LiquidTorque {
  ColumnD x, y, z;
  auto columns() { return std::tie(x, y, z); }
};
// The impulse (N s) the liquid gave each grain during the current outer step.
struct LiquidImpulse {
  ColumnD x, y, z;
  auto columns() { return std::tie(x, y, z); }
};

// The coupling's settings and what its last step measured (a world resource).
struct CouplingState {
  double h = 0;            // m, smoothing radius
  DragModel drag = &drag_laws()[0];
  bool rotational_drag = false;  // the liquid's torque on spinning grains
  bool shear_lift = false, spin_lift = false;  // lift forces (lift.hpp)
  bool needs_curl() const { return rotational_drag || shear_lift || spin_lift; }
  double eps_min = 0.2;
  LiquidFacts liquid;      // the liquid's density, viscosity, carrier volume and periodic axis
  bool fluid_nodes_only = false;  // shares over moving carriers only (coupling.share_with = "fluid_nodes")
  GrainShares shares;
  std::vector<double> node_eps;  // liquid fraction per carrier
  V3<double> grain_impulse{0, 0, 0};     // N s, sum over grains of the last outer step's tallies
  V3<double> reaction_impulse{0, 0, 0};  // N s, sum over every carrier of the reaction given to it
  V3<double> fluid_reaction{0, 0, 0};    // N s, the part given to moving carriers (the rest went to the tank)
};

// Attaches the grain columns and the CouplingState resource (the grains are in `world`).
void attach_coupling(const CouplingSpec& coupling, const LiquidFacts& liquid, World& world);

// The liquid's force on the grains, one more force term of the DEM step (the step itself is assembled
// with the scene's: systems/setup/coupled_simulation.cpp), with its torque when the coupling has rotational drag.
ForceTerm liquid_force_term(const CouplingSpec& coupling);
// The system that sets that force and tallies its impulse (after the contacts, before the closing kick).
void add_liquid_force(Schedule& step);
// The sub-step of grains held fixed (coupling.fixed_grains): the liquid's force and its impulse only.
std::unique_ptr<Schedule> fixed_grains_step();

// The pieces of the liquid's systems below that do not depend on the liquid's type (coupled_step.cpp).
namespace coupling_detail {
// c.shares of the owned grains over the carriers, or over the carriers of `rows` only (renumbered back to
// carrier rows); returns the grains' volume shared onto each carrier (m^3).
std::vector<double> share_grains(const Grains& g, const PointSet& carriers, const std::vector<std::uint32_t>* rows,
                                 CouplingState& c);
// The liquid's velocity and fraction (and with rotational drag its curl, from the carriers' positions) read at
// each grain through the shares; the grains' tallies zeroed.
void sample_at_grains(Grains& g, const CouplingState& c, const PointSet& carriers, const PointSet& velocity);
// The grains' tallied impulses shared onto the carriers as reaction per volume (N s/m^3); c.grain_impulse.
std::vector<V3<double>> reaction_per_volume(Grains& g, CouplingState& c, std::size_t carriers);
}  // namespace coupling_detail

// Shares, liquid fractions and the liquid read at the grains, from the grains' positions: the start of an
// outer step (coupling_prepare), also run on its own while the coupled simulation primes.
template <CoupledLiquid L>
void prepare_coupling(World& w) {
  L liquid(w);
  CouplingState& c = w.resources.get<CouplingState>();
  const PointSet carriers{liquid.position(0), liquid.position(1), liquid.position(2)};
  std::vector<std::uint32_t> moving;
  if (c.fluid_nodes_only)
    for (std::size_t i = 0; i < liquid.carriers(); ++i)
      if (liquid.moves(i)) moving.push_back(static_cast<std::uint32_t>(i));
  const std::vector<double> solid =
      coupling_detail::share_grains(w.grains, carriers, c.fluid_nodes_only ? &moving : nullptr, c);
  if (liquid.averaged()) {  // the carriers thin out where grains are: each stands for its own volume of mixture
    c.node_eps = liquid_fraction(solid, liquid.carrier_volumes(), c.eps_min);
    liquid.take_fraction(c.node_eps);
  } else {
    c.node_eps = liquid_fraction(solid, c.liquid.carrier_volume, c.eps_min);
  }
  coupling_detail::sample_at_grains(w.grains, c, carriers, {liquid.velocity(0), liquid.velocity(1), liquid.velocity(2)});
}

template <CoupledLiquid L>
struct CouplingPrepare : SystemBase<CouplingPrepare<L>> {
  using Reads = typename Join<gf::Reads<Position, Radius>, typename L::SampleReads>::type;
  using Writes =
      typename Join<gf::Writes<LiquidAtGrain, LiquidImpulse, CouplingState>, typename L::SampleWrites>::type;
  std::string_view name() const override { return "coupling_prepare"; }
  void run(World& w, const StepContext&) override { prepare_coupling<L>(w); }
};

// Minus each grain's tally, shared with the same weights, as momentum of the moving carriers.
template <CoupledLiquid L>
struct LiquidReaction : SystemBase<LiquidReaction<L>> {
  using Reads = typename Join<gf::Reads<LiquidAtGrain, LiquidImpulse>, typename L::ReactReads>::type;
  using Writes = typename Join<typename L::ReactWrites, gf::Writes<CouplingState>>::type;
  std::string_view name() const override { return "liquid_reaction"; }
  void run(World& w, const StepContext&) override {
    L liquid(w);
    CouplingState& c = w.resources.get<CouplingState>();
    const std::vector<V3<double>> per_volume = coupling_detail::reaction_per_volume(w.grains, c, liquid.carriers());
    c.reaction_impulse = c.fluid_reaction = {0, 0, 0};
    for (std::size_t n = 0; n < per_volume.size(); ++n) {
      const V3<double> dp = c.liquid.carrier_volume * per_volume[n];
      c.reaction_impulse = c.reaction_impulse + dp;
      if (!liquid.moves(n)) continue;
      c.fluid_reaction = c.fluid_reaction + dp;
      liquid.add_momentum(n, dp);
    }
  }
};

// The coupled step around the DEM sub-steps `inner` into `outer`: coupling_prepare, `substeps` runs of
// `inner`, liquid_reaction; the liquid's own step follows (the caller adds it). Returns the DEM sub-steps.
template <CoupledLiquid L>
SubSchedule& schedule_coupled_step(Schedule& outer, std::unique_ptr<Schedule> inner, int substeps) {
  outer.emplace<CouplingPrepare<L>>();
  SubSchedule& dem = outer.emplace<SubSchedule>("dem_substeps", substeps, std::move(inner));
  outer.emplace<LiquidReaction<L>>();
  return dem;
}

}  // namespace gf
