// The settings of the coupling of a liquid and grains, the scene's [coupling] table (read by
// systems/setup/coupled_scene.cpp, where each key is documented).
#pragma once

#include "systems/coupling/drag.hpp"

namespace gf {

struct CouplingSpec {
  int substeps = 1;
  bool substeps_computed = false;  // no coupling.substeps: from the DEM step limit
  double dem_step_limit = 0;       // s, run.dt_safety times the contact law's smallest period
  double smoothing_radius = 0;     // m
  DragModel drag = &drag_laws()[0];
  bool rotational_drag = false;    // rotational_drag = "dennis": the liquid's torque on spinning grains
  bool shear_lift = false;         // shear_lift = "saffman_mei" (lift.hpp)
  bool spin_lift = false;          // spin_lift = "oesterle_bui_dinh" (lift.hpp)
  double min_liquid_fraction = 0.2;
  bool modified_pressure = false;
  bool fixed_grains = false;
  bool fluid_nodes_only = false;  // share_with = "fluid_nodes"
  bool averaged = false;          // the liquid locally averaged (eps n0 as its number-density target)
};

}  // namespace gf
