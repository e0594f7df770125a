// Cubic sample cells for the composition measures of a binary mixture: Danckwerts' intensity of
// segregation (metrics.hpp) and Lacey's mixing index (mixing.hpp) both read the volume fraction of
// one species in each cell. A grain belongs whole to the cell that holds its centre (a grain across
// a cell face is not split) and adds its solid volume, 4/3 pi r^3, to that cell.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/grains.hpp"

namespace gf {

struct CellComposition {
  double volume_a = 0.0;  // m^3, solid volume of species A in the cell
  double volume = 0.0;    // m^3, solid volume of every grain in the cell
  int grains = 0;
};

struct CellBinning {
  // The occupied cells, in the order of their integer coordinates' key, so that sums over them do
  // not depend on how a hash map orders its buckets.
  std::vector<CellComposition> cells;
  // Totals over every owned grain (m^3, and m^6 for the sums of squared grain volumes).
  double volume_a = 0.0, volume = 0.0;
  double volume_sq_a = 0.0, volume_sq = 0.0;
  double fraction_a() const { return volume > 0.0 ? volume_a / volume : 0.0; }  // p
};

// Bins the owned grains into cubic cells of edge `cell` (m), aligned with the origin. Sequential:
// it runs at output intervals only, and a hash map keeps it independent of the domain's size.
CellBinning bin_cells(const Grains& g, std::int32_t type_a, double cell);

// Spread of the cells' fractions of A about p over the cells with at least `min_grains` grains,
// each cell weighted by its solid volume: sum V_i (f_i - p)^2 / sum V_i.
struct CellSpread {
  double variance = 0.0;     // sigma^2 (dimensionless)
  std::size_t cells = 0;     // cells counted
  std::int64_t grains = 0;   // grains in the counted cells
  double volume = 0.0;       // m^3, solid volume in the counted cells
};
CellSpread cell_spread(const CellBinning& b, double p, int min_grains);

}  // namespace gf
