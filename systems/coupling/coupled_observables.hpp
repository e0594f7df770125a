// What a coupled run reports per sample (series.csv columns, summary.json "final"): the liquid's columns
// (liquid_observables.hpp) followed by the grains' and the coupling's:
//   grains                       grains in the table
//   grain_x, grain_y, grain_z    m, mean position;  grain_vx, grain_vy, grain_vz  m/s, mean velocity
//   grain_kinetic_energy         J, translation and rotation
//   liquid_at_grain_vx, _vy, _vz  m/s, mean of the liquid's velocity u read at the grains (at the step's start)
//   grain_slip                   m/s, mean |u - v|
//   grain_liquid_fraction        mean liquid fraction at the grains;  min_liquid_fraction: over the nodes
//   liquid_force_x, _y, _z       N, the liquid's force summed over the grains (drag / eps plus buoyancy)
//   impulse_balance              N s, |grain impulse + liquid reaction| of the last step (rounding only)
#pragma once

#include <string>
#include <vector>

#include "engine/world.hpp"
#include "systems/mps/liquid_scene.hpp"

namespace gf {

std::vector<std::string> coupled_series_columns();
std::vector<double> sample_coupled(World& w, const LiquidScene& liquid);

}  // namespace gf
