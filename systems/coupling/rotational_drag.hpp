// The liquid's torque on a spinning grain (rotational drag), an option of the coupling ([coupling]
// rotational_drag = "dennis"; the seed's grains feel no liquid torque: I dw/dt = sum of contact torques):
//   T = -(rho_l / 2) (d/2)^5 C_R |Omega| Omega,   Omega = w - (1/2) curl u,   Re_R = |Omega| d^2 / nu
//   C_R = 64 pi / Re_R                          for Re_R <= 32 (Stokes: T = -pi mu d^3 Omega)
//   C_R = 12.9 / sqrt(Re_R) + 128.4 / Re_R      above (Dennis, Singh & Ingham 1980, measured for 32 < Re_R < 1000;
//                                               used beyond 1000 as the CFD-DEM codes that offer it do)
// with w the grain's spin, u the liquid's velocity at the grain, d its diameter. The two forms meet at 32 within
// 0.2 %. In a liquid turning as a rigid body at rate W (curl u = 2 W) a grain spinning at W feels no torque.
//
// The liquid's curl at a grain is the curl of a weighted least-squares linear fit u(x) = u_p + G (x - x_p) to
// the velocities of the nodes the grain shares its volume with (void_fraction.hpp), weighted by the same
// shares: exact for any linear field, and needing no more of the liquid than its nodes' positions and
// velocities.
#pragma once

#include <span>
#include <vector>

#include "systems/contact/vec3.hpp"
#include "systems/coupling/drag.hpp"
#include "systems/coupling/void_fraction.hpp"

namespace gf {

// C_R at rotational Reynolds number re (> 0).
double rotational_drag_coefficient(double re);

// The torque (N m) on a grain of diameter d (m) spinning at `omega_rel` (rad/s) relative to half the liquid's
// curl.
V3<double> rotational_drag_torque(const V3<double>& omega_rel, double d, const LiquidProps& liquid);

// The periodic axis (0, 1, 2; -1 none) and its period, for distances across it.
struct PeriodicAxis {
  int axis = -1;
  double lo = 0, hi = 0;
};

// curl u at each grain from the velocities of the nodes in its shares (rows of `nodes` and `velocity`); zero
// where a grain's nodes do not span three dimensions (fewer than four, or all in a plane).
std::vector<V3<double>> curl_at_grains(const GrainShares& s, const PointSet& grains, const PointSet& nodes,
                                       const PointSet& velocity, const PeriodicAxis& periodic);

}  // namespace gf
