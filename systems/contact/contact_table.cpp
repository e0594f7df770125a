#include "systems/contact/contact_table.hpp"

#include <algorithm>
#include <stdexcept>

#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

ContactTable::ContactTable(std::string law, std::size_t types, std::size_t width, std::vector<double> pair,
                           std::vector<double> wall, CriticalStep critical, double reach)
    : law_(std::move(law)),
      n_(types),
      width_(width),
      pp_(std::move(pair)),
      wall_(std::move(wall)),
      critical_(std::move(critical)),
      reach_(reach) {
  if (pp_.size() != n_ * n_ * width_ || wall_.size() != n_ * width_)
    throw std::invalid_argument("ContactTable: constant tables do not match the species count and the law's width");
}

void ContactTable::set_nominal_grains(const std::vector<double>& mass, const std::vector<double>& radius) {
  if (mass.size() != n_ || radius.size() != n_)
    throw std::invalid_argument("ContactTable: one nominal grain per species");
  nominal_mass_.assign(static_cast<std::size_t>(kMaxSpecies), 1.0);
  nominal_radius_.assign(static_cast<std::size_t>(kMaxSpecies), 1.0);
  std::copy(mass.begin(), mass.end(), nominal_mass_.begin());
  std::copy(radius.begin(), radius.end(), nominal_radius_.begin());
}

}  // namespace gf
