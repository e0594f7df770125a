#include "systems/contact/contact_table.hpp"

#include <stdexcept>

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

}  // namespace gf
