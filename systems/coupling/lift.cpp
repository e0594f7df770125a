#include "systems/coupling/lift.hpp"

#include <cmath>
#include <numbers>

namespace gf {

double mei_lift_factor(double re_p, double re_s) {
  const double beta = 0.5 * re_s / re_p;
  if (re_p <= 40.0) return (1.0 - 0.3314 * std::sqrt(beta)) * std::exp(-0.1 * re_p) + 0.3314 * std::sqrt(beta);
  return 0.0524 * std::sqrt(beta * re_p);
}

double spin_lift_coefficient(double re_p, double re_r) {
  return 0.45 + (re_r / re_p - 0.45) * std::exp(-0.05684 * std::pow(re_r, 0.4) * std::pow(re_p, 0.3));
}

V3<double> shear_lift(const V3<double>& slip, const V3<double>& vorticity, double d, const LiquidProps& liquid) {
  const double s = std::sqrt(dot(slip, slip)), W = std::sqrt(dot(vorticity, vorticity));
  if (!(s > 0) || !(W > 0)) return {0, 0, 0};
  const double mu = liquid.viscosity, rho = liquid.density;
  const double f = mei_lift_factor(rho * d * s / mu, rho * d * d * W / mu);
  return (1.615 * d * d * std::sqrt(rho * mu / W) * f) * cross(slip, vorticity);
}

V3<double> spin_lift(const V3<double>& slip, const V3<double>& relative_spin, double d, const LiquidProps& liquid) {
  const double s = std::sqrt(dot(slip, slip)), O = std::sqrt(dot(relative_spin, relative_spin));
  if (!(s > 0) || !(O > 0)) return {0, 0, 0};
  const double mu = liquid.viscosity, rho = liquid.density;
  const double C = spin_lift_coefficient(rho * d * s / mu, rho * d * d * O / mu);
  return (std::numbers::pi / 8.0 * rho * d * d * C * s / O) * cross(relative_spin, slip);
}

}  // namespace gf
