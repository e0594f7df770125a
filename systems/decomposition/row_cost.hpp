// What one owned row costs a step, the weight the ranks' boxes are balanced by (rcb.hpp): 1 for the
// row's own work (integration, walls, its share of the neighbour search) plus kPairCost for each pair
// of the neighbour list it takes part in, a pair between two owned rows counted half at each, a pair
// with a ghost row (evaluated on this rank alone) whole at the owned row. The list's pairs, not the
// touching ones, because the pair kernel evaluates every listed pair.
//
// kPairCost is measured: the pair kernel on the settled seed-000 drum (47,108 grains, 157,621 list
// pairs, one thread) takes 1.92 ms a step, 12.2 ns a list pair (studies/performance/results/pair_contact.json, the
// median of BM_PairForces/simd/threads:1); the rest of the flowing drum's step takes 2.50 s of its
// 6.49 s over 2,000 steps, 26.5 ns a row (studies/performance/results/drum_time_split_flowing.json). 12.2 / 26.5 = 0.46.
// A dense bed (about 3.4 list pairs a row) then weighs 2.5 times a loose gas (none).
#pragma once

#include <vector>

#include "engine/grains.hpp"
#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

inline constexpr double kPairCost = 0.46;

// The cost of each owned row (g.n_owned of them) from `list` (a list over these rows and the ghost
// rows after them); every cost 1 when the list does not match the rows (none built yet).
std::vector<double> row_costs(const Grains& g, const NeighborList& list, double pair_cost = kPairCost);

}  // namespace gf
