#include "systems/decomposition/row_cost.hpp"

namespace gf {

std::vector<double> row_costs(const Grains& g, const NeighborList& list, double pair_cost) {
  const std::size_t n = g.n_owned;
  std::vector<double> cost(n, 1.0);
  if (list.offsets.size() != n + 1) return cost;
  for (std::size_t i = 0; i < n; ++i)
    for (std::uint32_t k = list.offsets[i]; k < list.offsets[i + 1]; ++k) {
      const std::uint32_t j = list.j[k];
      if (j < n) {
        cost[i] += 0.5 * pair_cost;
        cost[j] += 0.5 * pair_cost;
      } else {
        cost[i] += pair_cost;
      }
    }
  return cost;
}

}  // namespace gf
