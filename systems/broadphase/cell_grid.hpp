// Uniform cell grid by counting sort (count, prefix scan, stable scatter).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace gf {

struct CellGrid {
  std::array<double, 3> origin{};
  double cell = 0.0;                  // m, edge of a cubic cell
  std::array<std::int64_t, 3> dims{};  // cells per axis
  std::vector<std::uint32_t> cell_of;  // cell index per row (in the order rows were given)
  std::vector<std::uint32_t> start;    // size cells + 1: rows of cell c are [start[c], start[c+1]) in sorted order
  std::vector<std::uint32_t> order;    // sorted position -> row given

  std::size_t cells() const { return start.empty() ? 0 : start.size() - 1; }

  // Bins n points with cell edge at least `min_cell`. The grid spans the points' bounding box; if
  // that would take more than `max_cells` cells the edge grows (slower, never wrong). Throws on a
  // non-finite coordinate, naming the row.
  void build(std::span<const double> x, std::span<const double> y, std::span<const double> z, double min_cell,
             std::size_t max_cells = std::size_t(1) << 24);
};

}  // namespace gf
