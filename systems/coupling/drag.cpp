#include "systems/coupling/drag.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gf {

namespace {

constexpr double kSwitch = 0.8;  // the seed's liquid fraction between Ergun and Wen-Yu

void check(double eps, double slip, double d, const LiquidProps& l) {
  if (!(eps > 0.0 && eps <= 1.0) || !(slip >= 0.0) || !std::isfinite(slip) || !(d > 0.0) || !std::isfinite(d) ||
      !(l.density > 0.0) || !(l.viscosity > 0.0))
    throw std::invalid_argument("drag: needs 0 < eps <= 1, a finite slip >= 0, d > 0, and a liquid of positive "
                                "density and viscosity");
}

// Ergun's beta / (1 - eps).
double ergun(double eps, double slip, double d, const LiquidProps& l) {
  return 150.0 * (1.0 - eps) / eps * l.viscosity / (d * d) + 1.75 * l.density / d * slip;
}

// Wen-Yu's beta / (1 - eps); at zero slip its limit, 18 mu eps^-2.65 / d^2 (Stokes' drag at eps = 1).
double wen_yu(double eps, double slip, double d, const LiquidProps& l) {
  const double re = eps * l.density * d * slip / l.viscosity;
  if (!(re > 0.0)) return 18.0 * l.viscosity / (d * d) * std::pow(eps, -2.65);
  return 0.75 * schiller_naumann(re) * eps / d * l.density * std::pow(eps, -2.65) * slip;
}

// The seed's switch: Ergun at eps <= 0.8, Wen-Yu above.
double ergun_wen_yu(double eps, double slip, double d, const LiquidProps& l) {
  return eps <= kSwitch ? ergun(eps, slip, d, l) : wen_yu(eps, slip, d, l);
}

// Huilin & Gidaspow's blend of the two, continuous across 0.8.
double blend(double eps, double slip, double d, const LiquidProps& l) {
  const double phi = 0.5 + std::atan(262.5 * (0.2 - (1.0 - eps))) / std::numbers::pi;
  return (1.0 - phi) * ergun(eps, slip, d, l) + phi * wen_yu(eps, slip, d, l);
}

constexpr DragLaw kLaws[] = {
    {"ergun_wen_yu", "Ergun at eps <= 0.8, Wen-Yu above (seed 003's switch; jumps at 0.8)", ergun_wen_yu},
    {"blend", "Huilin & Gidaspow (2003): Ergun and Wen-Yu blended, continuous across eps = 0.8", blend},
};

}  // namespace

std::span<const DragLaw> drag_laws() { return kLaws; }

std::vector<std::string> drag_law_names() {
  std::vector<std::string> names;
  for (const DragLaw& l : kLaws) names.emplace_back(l.name);
  return names;
}

const DragLaw& drag_law(std::string_view name) {
  for (const DragLaw& l : kLaws)
    if (l.name == name) return l;
  std::string known;
  for (const DragLaw& l : kLaws) known += (known.empty() ? "'" : ", '") + std::string(l.name) + "'";
  throw std::invalid_argument("no drag law is named '" + std::string(name) + "' (registered: " + known + ")");
}

double schiller_naumann(double re) {
  if (!(re > 0.0)) throw std::invalid_argument("schiller_naumann: the Reynolds number must be positive");
  return re <= 1000.0 ? 24.0 / re * (1.0 + 0.15 * std::pow(re, 0.687)) : 0.44;
}

double drag_per_volume(double eps, double slip, double d, const LiquidProps& liquid, const DragLaw& law) {
  check(eps, slip, d, liquid);
  return law.per_volume(eps, slip, d, liquid);
}

V3<double> drag_force(const V3<double>& u, const V3<double>& v, double eps, double d, const LiquidProps& liquid,
                      const DragLaw& law) {
  const V3<double> w = u - v;
  const double volume = std::numbers::pi / 6.0 * d * d * d;
  return (drag_per_volume(eps, std::sqrt(dot(w, w)), d, liquid, law) * volume) * w;
}

V3<double> liquid_force(const V3<double>& u, const V3<double>& v, double eps, double d, const LiquidProps& liquid,
                        const V3<double>& gravity, const DragLaw& law) {
  const double volume = std::numbers::pi / 6.0 * d * d * d;
  return (1.0 / eps) * drag_force(u, v, eps, d, liquid, law) - (volume * liquid.density) * gravity;
}

double drag_switch_jump(double slip, double d, const LiquidProps& liquid) {
  check(kSwitch, slip, d, liquid);
  return wen_yu(kSwitch, slip, d, liquid) / ergun(kSwitch, slip, d, liquid);
}

}  // namespace gf
