// Contact parameters of seed 000 (Zhao & Cheng 2007, Tables 1-3) and the per type-pair table of
// derived constants. Damping comes from restitution with the effective mass of each term:
//   eta = 2 sqrt(m k) ln(1/e) / sqrt(pi^2 + ln^2(1/e))   (e > 0),   eta = 2 sqrt(m k)   (e = 0)
// normal m = m_i m_j/(m_i+m_j), tangential 2/7 of that, rolling I = I_i I_j/(I_i+I_j);
// for a wall contact the particle's own m_i and I_i.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace gf {

// What a scene states for one pair of species (or species and wall).
struct ContactParams {
  double kn = 0;  // N/m, normal spring
  double kt = 0;  // N/m, tangential spring
  double kr = 0;  // N m/rad, rolling spring
  double en = 1;  // normal restitution, [0, 1]
  double et = 1;  // tangential restitution
  double er = 1;  // rolling restitution
  double friction = 0;          // sliding friction coefficient f_s
  double rolling_friction = 0;  // f_r, m (rolling torque cap f_r |F_n|)
};

// Constants a kernel uses, precomputed once per type pair.
struct PairCoeffs {
  double kn, kt, kr;
  double eta_n, eta_t, eta_r;  // N s/m, N s/m, N m s/rad
  double fs, fr;
};

// Mass properties of one species (species are monodisperse: one diameter each).
struct SpeciesMass {
  double mass;     // kg
  double inertia;  // kg m^2
};

double damping_coefficient(double m_eff, double k, double e);
// Period of the damped contact oscillation, T = 2 sqrt(pi^2 + ln^2 e) sqrt(m/k) (Table 3).
double collision_period(double m_eff, double k, double e);

struct CriticalStep {
  double period;     // s, smallest collision period over all terms and pairs
  std::string term;  // e.g. "tangential, small-large"
};

class ContactTable {
 public:
  ContactTable() = default;
  // params_pp is n*n (symmetric), params_wall has n entries.
  ContactTable(std::vector<SpeciesMass> species, std::vector<ContactParams> params_pp,
               std::vector<ContactParams> params_wall, std::vector<std::string> names);

  std::size_t types() const { return n_; }
  const PairCoeffs& pair(std::size_t a, std::size_t b) const { return pp_[a * n_ + b]; }
  const PairCoeffs& wall(std::size_t a) const { return wall_[a]; }
  const PairCoeffs* pair_data() const { return pp_.data(); }
  const PairCoeffs* wall_data() const { return wall_.data(); }
  const ContactParams& params(std::size_t a, std::size_t b) const { return params_pp_[a * n_ + b]; }
  const ContactParams& wall_params(std::size_t a) const { return params_wall_[a]; }

  // The smallest collision period (Table 3) over every type pair, every wall and all three terms.
  CriticalStep critical_period() const;

 private:
  std::size_t n_ = 0;
  std::vector<SpeciesMass> species_;
  std::vector<ContactParams> params_pp_, params_wall_;
  std::vector<std::string> names_;
  std::vector<PairCoeffs> pp_, wall_;
};

}  // namespace gf
