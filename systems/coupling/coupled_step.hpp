// The liquid and the grains in one step (seed 003's multi-rate coupling). The liquid's step is the outer
// schedule; the DEM step runs k times inside it at dt/k as one of its systems (engine/sub_schedule.hpp):
//   coupling_prepare   shares of every grain on the nodes within h (void_fraction.hpp), the nodes' liquid
//                      fraction eps_i, and the liquid's velocity and fraction read at each grain
//   dem_substeps       k DEM steps (with coupling.fixed_grains only liquid_force, the grains staying put);
//                      in each, liquid_force sets F = F_d/eps - V_p rho_l g on every grain
//                      (drag.hpp: the scene's drag law with the grain's own velocity, the liquid's read at
//                      the step's start; buoyancy in Archimedes' form) and adds the impulse the
//                      integrator's two half-kicks give it, h/2 (F_old + F_new), to the grain's tally
//   liquid_reaction    minus each grain's tally, shared with the same weights, changes the nodes'
//                      momentum: du_i = -(1/(rho V_i)) sum_p w_ip J_p, V_i = l0^3; fixed wall and dummy
//                      nodes pass their share to the tank. Grain impulse plus liquid reaction is zero to
//                      rounding (CouplingState's totals; tests/coupled_step_test.cpp)
//   the liquid's step  (liquid_step.hpp), from the kicked velocities
// The liquid itself is not yet locally averaged: its density and number density do not see eps.
#pragma once

#include <cstdint>
#include <memory>
#include <tuple>
#include <vector>

#include "engine/column.hpp"
#include "engine/schedule.hpp"
#include "systems/coupling/drag.hpp"
#include "systems/coupling/void_fraction.hpp"
#include "systems/integrate/force_terms.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/coupling/coupling_settings.hpp"
#include "systems/mps/liquid_scene.hpp"

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
  Column<std::int32_t> row;
  auto columns() { return std::tie(ux, uy, uz, eps, row); }
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
  double eps_min = 0.2;
  double node_volume = 0;  // m^3, l0^3
  Periodicity periodic;    // the liquid's periodic axis: shares reach across it
  bool fluid_nodes_only = false;  // shares over fluid nodes only (coupling.share_with = "fluid_nodes")
  LiquidProps liquid;
  GrainShares shares;
  std::vector<double> node_eps;  // liquid fraction per node
  V3<double> grain_impulse{0, 0, 0};     // N s, sum over grains of the last outer step's tallies
  V3<double> reaction_impulse{0, 0, 0};  // N s, sum over every node of the reaction given to it
  V3<double> fluid_reaction{0, 0, 0};    // N s, the part given to fluid nodes (the rest went to the tank)
};

// Attaches the grain columns and the CouplingState resource (the liquid and the grains are in `world`).
void attach_coupling(const CouplingSpec& coupling, const LiquidScene& liquid, World& world);

// The liquid's force on the grains, one more force term of the DEM step (the step itself is assembled
// with the scene's: systems/setup/coupled_simulation.cpp).
ForceTerm liquid_force_term();
// The system that sets that force and tallies its impulse (after the contacts, before the closing kick).
void add_liquid_force(Schedule& step);
// The sub-step of grains held fixed (coupling.fixed_grains): the liquid's force and its impulse only.
std::unique_ptr<Schedule> fixed_grains_step();

class SubSchedule;
// The coupled step around the DEM sub-steps `inner` into `outer`: coupling_prepare, `substeps` runs of
// `inner`, liquid_reaction, then the liquid's step; returns the DEM sub-steps.
SubSchedule& schedule_coupled_step(Schedule& outer, std::unique_ptr<Schedule> inner, int substeps, bool driven);

// The systems of the outer step that the coupled simulation runs on its own while priming.
void prepare_coupling(World& world);

}  // namespace gf
