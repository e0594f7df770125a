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
  std::array<std::int64_t, 3> dims{};  // cells per axis (x, y, z)
  // The axes from fastest to slowest varying in the cell index: fewest cells first, so that the
  // rows of neighbouring cells, stored in cell order, are never more than two short axes apart
  // (a thin drum along z would otherwise put its z neighbours a quarter of all rows away).
  std::array<int, 3> axes{0, 1, 2};
  std::vector<std::uint32_t> cell_of;  // cell index per row (in the order rows were given)
  std::vector<std::uint32_t> start;    // size cells + 1: rows of cell c are [start[c], start[c+1]) in sorted order
  std::vector<std::uint32_t> order;    // sorted position -> row given

  std::size_t cells() const { return start.empty() ? 0 : start.size() - 1; }
  // Cell index of integer cell coordinates c (x, y, z).
  std::size_t flat(const std::array<std::int64_t, 3>& c) const {
    return static_cast<std::size_t>((c[axes[2]] * dims[axes[1]] + c[axes[1]]) * dims[axes[0]] + c[axes[0]]);
  }
  // Its inverse: the cell coordinates (x, y, z) of a cell index.
  std::array<std::int64_t, 3> coords(std::size_t flat_index) const {
    const auto k = static_cast<std::int64_t>(flat_index);
    std::array<std::int64_t, 3> c{};
    c[axes[0]] = k % dims[axes[0]];
    c[axes[1]] = (k / dims[axes[0]]) % dims[axes[1]];
    c[axes[2]] = k / (dims[axes[0]] * dims[axes[1]]);
    return c;
  }

  // Bins n points with cell edge at least `min_cell`. The grid spans the points' bounding box; if
  // that would take more than `max_cells` cells the edge grows (slower, never wrong). Throws on a
  // non-finite coordinate, naming the row.
  void build(std::span<const double> x, std::span<const double> y, std::span<const double> z, double min_cell,
             std::size_t max_cells = std::size_t(1) << 24);
};

}  // namespace gf
