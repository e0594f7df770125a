// The per type-pair constants of the scene's contact law, computed once at load: for every pair
// of species and for every species against the walls, the law's kConstants doubles in the law's
// order, and the critical time step over every pair. The table knows the law by name only; the
// template below builds it from a law's declarations (contact_law.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "systems/contact/contact_law.hpp"

namespace gf {

struct CriticalStep {
  double period;     // s, the smallest time-step term over all pairs
  std::string term;  // e.g. "tangential, small-large"
};

class ContactTable {
 public:
  ContactTable() = default;
  // pair: types*types*width doubles (symmetric), wall: types*width.
  ContactTable(std::string law, std::size_t types, std::size_t width, std::vector<double> pair,
               std::vector<double> wall, CriticalStep critical, double reach = 0.0);

  const std::string& law() const { return law_; }
  std::size_t types() const { return n_; }
  std::size_t width() const { return width_; }
  // The law's constants for species a against b, and against a wall.
  const double* pair(std::size_t a, std::size_t b) const { return &pp_[(a * n_ + b) * width_]; }
  const double* wall(std::size_t a) const { return &wall_[a * width_]; }
  const CriticalStep& critical_period() const { return critical_; }
  // Species whose grains differ in size: the nominal grain each species' constants were computed for
  // (size_scaling.hpp); the drivers then rescale the constants to each contact's grains. Arrays of
  // kMaxSpecies entries, so that a batch may gather them by type.
  void set_nominal_grains(const std::vector<double>& mass, const std::vector<double>& radius);
  bool sized() const { return !nominal_mass_.empty(); }
  const double* nominal_mass() const { return nominal_mass_.data(); }
  const double* nominal_radius() const { return nominal_radius_.data(); }
  // m: the largest reach of a pair beyond touching (a ReachingLaw's; 0 for laws acting in contact),
  // how much further than r_i + r_j + skin the neighbour search must look.
  double reach() const { return reach_; }

 private:
  std::string law_;
  std::size_t n_ = 0, width_ = 0;
  std::vector<double> pp_, wall_;
  CriticalStep critical_{std::numeric_limits<double>::infinity(), ""};
  double reach_ = 0.0;
  std::vector<double> nominal_mass_, nominal_radius_;
};

// The table of law L for species `bodies` (named `names`), with the scene's parameters per pair
// (params_pp, n*n, symmetric) and against walls (params_wall, n).
template <class L>
ContactTable make_contact_table(const std::vector<ContactBody<typename L::Material>>& bodies,
                                const std::vector<std::string>& names,
                                const std::vector<typename L::Params>& params_pp,
                                const std::vector<typename L::Params>& params_wall) {
  const std::size_t n = bodies.size();
  constexpr std::size_t K = L::kConstants;
  static_assert(K <= kMaxConstants, "a law declares at most kMaxConstants constants");
  std::vector<double> pp(n * n * K), pw(n * K);
  CriticalStep best{std::numeric_limits<double>::infinity(), ""};
  auto consider = [&](const std::vector<StepTerm>& terms, const std::string& who) {
    for (const StepTerm& t : terms)
      if (t.time < best.period) best = {t.time, t.term + ", " + who};
  };
  ContactBody<typename L::Material> wall;
  wall.wall = true;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      const auto c = L::constants(bodies[a], bodies[b], params_pp[a * n + b]);
      std::copy(c.begin(), c.end(), pp.begin() + static_cast<std::ptrdiff_t>((a * n + b) * K));
      if (b >= a) consider(L::critical_terms(bodies[a], bodies[b], params_pp[a * n + b]), names[a] + "-" + names[b]);
    }
    const auto c = L::constants(bodies[a], wall, params_wall[a]);
    std::copy(c.begin(), c.end(), pw.begin() + static_cast<std::ptrdiff_t>(a * K));
    consider(L::critical_terms(bodies[a], wall, params_wall[a]), names[a] + "-wall");
  }
  double reach = 0.0;
  if constexpr (ReachingLaw<L>)
    for (std::size_t q = 0; q < n * n; ++q) reach = std::max(reach, pp[q * K + L::kReach]);
  return ContactTable(std::string(L::name), n, K, std::move(pp), std::move(pw), best, reach);
}

}  // namespace gf
