// Lift on a grain in the liquid, options of the coupling ([coupling] shear_lift, spin_lift; the seed's grains
// feel drag and buoyancy only). With u the liquid's velocity and W = curl u its vorticity at the grain, v and w
// the grain's velocity and spin, d its diameter, rho and mu the liquid's density and dynamic viscosity:
//
// Shear lift, Saffman's force with Mei's correction for finite Reynolds number (shear_lift = "saffman_mei"; as in
// Crowe, Sommerfeld & Tsuji, "Multiphase flows with droplets and particles", 1998, and CFD-DEM codes' MeiLift):
//   F = 1.615 d^2 sqrt(rho mu / |W|) f (u - v) x W
//   Re_p = rho d |u - v| / mu,  Re_s = rho d^2 |W| / mu,  beta = Re_s / (2 Re_p)
//   f = (1 - 0.3314 sqrt(beta)) exp(-Re_p / 10) + 0.3314 sqrt(beta)   for Re_p <= 40
//   f = 0.0524 sqrt(beta Re_p)                                           above
// A grain lagging the liquid in a shear flow is pushed towards the faster liquid.
//
// Spin lift, the Magnus force of Rubinow & Keller with Oesterle & Bui Dinh's coefficient (spin_lift =
// "oesterle_bui_dinh"):
//   F = (pi / 8) rho d^2 C |u - v| (O x (u - v)) / |O|,   O = W / 2 - w (the liquid's spin relative to the grain's)
//   Re_r = rho d^2 |O| / mu,  C = 0.45 + (Re_r / Re_p - 0.45) exp(-0.05684 Re_r^0.4 Re_p^0.3)
// which tends to Rubinow & Keller's (pi / 8) rho d^3 O x (u - v) as Re_p -> 0.
//
// Both vanish with the slip or with the rotation they feed on. Their force joins the drag in the grain's tally,
// so the liquid takes it back (coupled_step.hpp).
#pragma once

#include "systems/contact/vec3.hpp"
#include "systems/coupling/drag.hpp"

namespace gf {

// Mei's correction f at particle Reynolds number re_p > 0 and shear Reynolds number re_s >= 0.
double mei_lift_factor(double re_p, double re_s);

// Oesterle & Bui Dinh's spin-lift coefficient at re_p > 0 and re_r >= 0.
double spin_lift_coefficient(double re_p, double re_r);

// Saffman-Mei shear lift (N) for slip u - v (m/s) and vorticity W (1/s) at the grain.
V3<double> shear_lift(const V3<double>& slip, const V3<double>& vorticity, double d, const LiquidProps& liquid);

// Magnus spin lift (N) for slip u - v and the liquid's spin relative to the grain's, O = W/2 - w (rad/s).
V3<double> spin_lift(const V3<double>& slip, const V3<double>& relative_spin, double d, const LiquidProps& liquid);

}  // namespace gf
