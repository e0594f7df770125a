// What a liquid run reports per sample (series.csv columns, summary.json "final"):
//   kinetic_energy     J (2D: J per metre of depth), sum 1/2 rho l0^d |u|^2 over fluid nodes
//   max_speed          m/s;  cfl: max |u| dt / l0;  max_density_ratio: max n*/n0 of the last step
//   surface_nodes      nodes on the free surface;  ppe_iterations, ppe_residual: last PPE solve
//   surge_front        m, largest x of a fluid node still attached to the liquid (n >= n0/2: a droplet flung
//                      ahead is not the front) plus l0/2, the edge of its volume (dam-break leading edge; at
//                      t = 0 it is the column's face)
//   bottom_pressure    Pa, mean pressure of the floor's wall nodes (the layer centred l0/2 below the floor face
//                      y = geometry lo.y) over the middle half of the floor in x (and z). MPS holds p = 0 on the
//                      free-surface nodes, whose centres lie l0/2 below the liquid's top, so these wall nodes lie
//                      exactly the fill height H below the p = 0 level: the hydrostatic reference is rho g H.
//   centre_velocity    m/s, mean x velocity of fluid nodes within l0 of the channel's mid-plane (y centre; in
//                      3D also z centre) or the pipe's axis: the centre-line speed of a periodic flow
//   mean_velocity      m/s, mean velocity of the fluid nodes along the periodic axis (x when there is none):
//                      the superficial velocity of a periodic flow, what a [drive] controls (flow_drive.hpp)
//   body_force         m/s^2, the body force along that axis (under a [drive], the control; rho times it is
//                      the driving pressure gradient)
#pragma once

#include <string>
#include <vector>

#include "engine/world.hpp"
#include "systems/mps/liquid_scene.hpp"

namespace gf {

std::vector<std::string> liquid_series_columns();
std::vector<double> sample_liquid(World& w, const LiquidScene& s);

// Fluid-node kinetic energy (J, or J/m in 2D).
double liquid_kinetic_energy(const FluidNodes& f, const LiquidParams& lp);

}  // namespace gf
