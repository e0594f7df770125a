// The liquid's force on a grain in a locally averaged liquid, as seed 003 writes it
// (../shared/spec/003-mps-dem-pipe.md, "Coupling"):
//   drag      F_d = beta / (1 - eps) (u - v) V_p
//   on grain  F_int = F_d / eps - V_p rho_l g        (drag plus buoyancy; g the gravity vector)
// with eps the liquid's volume fraction at the grain, u the liquid's and v the grain's velocity,
// V_p the grain's volume, d its diameter, rho_l and mu the liquid's density and dynamic viscosity.
// The momentum exchange coefficient beta (kg m^-3 s^-1):
//   Ergun (eps <= 0.8)   beta = 150 (1 - eps)^2 / eps mu / d^2 + 1.75 (1 - eps) rho_l / d |u - v|
//   Wen-Yu (eps > 0.8)   beta = 0.75 C_d eps (1 - eps) / d rho_l eps^-2.65 |u - v|
//   C_d = 24 / Re (1 + 0.15 Re^0.687) for Re <= 1000, else 0.44 (Schiller-Naumann), Re = eps rho_l d |u - v| / mu
// beta / (1 - eps) is what the force needs and what these functions return: it stays finite as eps
// goes to 1 (a lone grain), where the Wen-Yu form becomes the standard drag (1/2) rho_l C_d A |w| w.
//
// The seed switches at eps = 0.8, where the two forms do not meet: the jump is reported by
// drag_switch_jump() and shown in tests/drag_test.cpp. The blended form (Huilin & Gidaspow 2003),
// beta = (1 - phi) beta_Ergun + phi beta_WenYu with phi = 1/2 + atan(262.5 (0.2 - (1 - eps))) / pi,
// is continuous and is offered as an option. Both forms of beta agree with Ergun's packed-bed
// pressure drop in a fixed bed through F_int = F_d / eps (the test checks it to rounding).
//
// The laws are a registry, as the contact laws are: a scene names one in [coupling] drag, and adding
// a law is its function beta / (1 - eps), its test and its line in drag_laws() (drag.cpp).
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "systems/contact/vec3.hpp"

namespace gf {

struct LiquidProps {
  double density = 1000.0;   // kg/m^3
  double viscosity = 1e-3;   // Pa s (dynamic)
};

// A drag law: its name in a scene, one line of what it is, and beta / (1 - eps) in kg m^-3 s^-1 for
// liquid fraction eps, slip speed |u - v| (m/s) and grain diameter d (m), arguments already checked.
struct DragLaw {
  std::string_view name;
  std::string_view meaning;
  double (*per_volume)(double eps, double slip, double d, const LiquidProps& liquid);
};

// The registered laws, the scene's default (the seed's Ergun / Wen-Yu switch) first.
std::span<const DragLaw> drag_laws();
std::vector<std::string> drag_law_names();
// The law of that name; std::invalid_argument naming the registered ones when none is.
const DragLaw& drag_law(std::string_view name);
// What a scene's coupling and the coupling's state hold.
using DragModel = const DragLaw*;

// Schiller-Naumann's drag coefficient of a sphere at particle Reynolds number re (> 0).
double schiller_naumann(double re);

// beta / (1 - eps) in kg m^-3 s^-1 for a grain of diameter d (m) at slip speed |u - v| (m/s) in
// liquid of volume fraction eps (0 < eps <= 1). std::invalid_argument outside those ranges.
double drag_per_volume(double eps, double slip, double d, const LiquidProps& liquid,
                       const DragLaw& law = drag_laws()[0]);

// The drag force F_d (N) on a grain of diameter d moving at v in liquid moving at u.
V3<double> drag_force(const V3<double>& u, const V3<double>& v, double eps, double d, const LiquidProps& liquid,
                      const DragLaw& law = drag_laws()[0]);

// The liquid's whole force on the grain, F_d / eps - V_p rho_l g (N), g the gravity vector (m/s^2).
V3<double> liquid_force(const V3<double>& u, const V3<double>& v, double eps, double d, const LiquidProps& liquid,
                        const V3<double>& gravity, const DragLaw& law = drag_laws()[0]);

// Wen-Yu over Ergun at eps = 0.8 (the seed's switch) for that slip and grain: 1 would be continuous.
double drag_switch_jump(double slip, double d, const LiquidProps& liquid);

}  // namespace gf
