#include "systems/contact/contact_params.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gf {

double damping_coefficient(double m_eff, double k, double e) {
  if (e <= 0.0) return 2.0 * std::sqrt(m_eff * k);
  const double l = std::log(1.0 / e);
  return 2.0 * std::sqrt(m_eff * k) * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

double collision_period(double m_eff, double k, double e) {
  const double l = e > 0.0 ? std::log(e) : 0.0;  // e = 0 is critically damped; use the undamped bound
  return 2.0 * std::sqrt(std::numbers::pi * std::numbers::pi + l * l) * std::sqrt(m_eff / k);
}

namespace {
PairCoeffs derive(const ContactParams& p, double m_eff, double i_eff) {
  return {p.kn,
          p.kt,
          p.kr,
          damping_coefficient(m_eff, p.kn, p.en),
          damping_coefficient(2.0 / 7.0 * m_eff, p.kt, p.et),
          p.kr > 0.0 ? damping_coefficient(i_eff, p.kr, p.er) : 0.0,
          p.friction,
          p.rolling_friction};
}
}  // namespace

ContactTable::ContactTable(std::vector<SpeciesMass> species, std::vector<ContactParams> params_pp,
                           std::vector<ContactParams> params_wall, std::vector<std::string> names)
    : n_(species.size()),
      species_(std::move(species)),
      params_pp_(std::move(params_pp)),
      params_wall_(std::move(params_wall)),
      names_(std::move(names)) {
  if (params_pp_.size() != n_ * n_ || params_wall_.size() != n_ || names_.size() != n_)
    throw std::invalid_argument("ContactTable: parameter tables do not match the species count");
  pp_.resize(n_ * n_);
  wall_.resize(n_);
  for (std::size_t a = 0; a < n_; ++a) {
    for (std::size_t b = 0; b < n_; ++b) {
      const SpeciesMass& A = species_[a];
      const SpeciesMass& B = species_[b];
      const double m = A.mass * B.mass / (A.mass + B.mass);
      const double i = A.inertia * B.inertia / (A.inertia + B.inertia);
      pp_[a * n_ + b] = derive(params_pp_[a * n_ + b], m, i);
    }
    wall_[a] = derive(params_wall_[a], species_[a].mass, species_[a].inertia);
  }
}

CriticalStep ContactTable::critical_period() const {
  CriticalStep best{std::numeric_limits<double>::infinity(), ""};
  auto consider = [&](double t, const std::string& what) {
    if (t < best.period) best = {t, what};
  };
  auto terms = [&](const ContactParams& p, double m, double i, const std::string& who) {
    if (p.kn > 0) consider(collision_period(m, p.kn, p.en), "normal, " + who);
    if (p.kt > 0) consider(collision_period(2.0 / 7.0 * m, p.kt, p.et), "tangential, " + who);
    if (p.kr > 0) consider(collision_period(i, p.kr, p.er), "rolling, " + who);
  };
  for (std::size_t a = 0; a < n_; ++a) {
    for (std::size_t b = a; b < n_; ++b) {
      const SpeciesMass& A = species_[a];
      const SpeciesMass& B = species_[b];
      terms(params_pp_[a * n_ + b], A.mass * B.mass / (A.mass + B.mass),
            A.inertia * B.inertia / (A.inertia + B.inertia), names_[a] + "-" + names_[b]);
    }
    terms(params_wall_[a], species_[a].mass, species_[a].inertia, names_[a] + "-wall");
  }
  return best;
}

}  // namespace gf
