// Uniform cell grid by counting sort (count, prefix scan, stable scatter).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace gf {

struct CellGrid {
  // Grid axis a runs along coordinate axis[a] of the points; axis 0 varies fastest in cell order.
  std::array<int, 3> axis{0, 1, 2};
  std::array<double, 3> origin{};
  double cell = 0.0;                  // m, edge of a cubic cell
  std::array<std::int64_t, 3> dims{};  // cells per axis
  std::vector<std::uint32_t> cell_of;  // cell index per row (in the order rows were given)
  std::vector<std::uint32_t> start;    // size cells + 1: rows of cell c are [start[c], start[c+1]) in sorted order
  std::vector<std::uint32_t> order;    // sorted position -> row given

  std::size_t cells() const { return start.empty() ? 0 : start.size() - 1; }

  // Bins n points with cell edge at least `min_cell`. The grid spans the points' bounding box; if
  // that would take more than `max_cells` cells the edge grows (slower, never wrong). Throws on a
  // non-finite coordinate, naming the row. With `shortest_fastest`, the grid axes are the coordinate
  // axes ordered by the points' extent, shortest first: cells that touch are then closest in cell
  // order (in a thin drum, neighbours across the thin axis are a few cells apart, not a layer).
  void build(std::span<const double> x, std::span<const double> y, std::span<const double> z, double min_cell,
             std::size_t max_cells = std::size_t(1) << 24, bool shortest_fastest = false);
};

}  // namespace gf
