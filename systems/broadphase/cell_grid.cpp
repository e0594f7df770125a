#include "systems/broadphase/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "engine/run_loop.hpp"

namespace gf {

namespace {
struct Box {
  std::array<double, 3> lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::infinity()};
  std::array<double, 3> hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
  std::int64_t bad = -1;
};
}  // namespace

void CellGrid::build(std::span<const double> x, std::span<const double> y, std::span<const double> z,
                     double min_cell, std::size_t max_cells, bool shortest_fastest) {
  const std::size_t n = x.size();
  const std::span<const double> coord[3] = {x, y, z};
  const Box box = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n, 4096), Box{},
      [&](const tbb::blocked_range<std::size_t>& r, Box b) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const double p[3] = {x[i], y[i], z[i]};
          for (int d = 0; d < 3; ++d) {
            if (!std::isfinite(p[d])) {
              if (b.bad < 0 || static_cast<std::int64_t>(i) < b.bad) b.bad = static_cast<std::int64_t>(i);
              continue;
            }
            b.lo[d] = std::min(b.lo[d], p[d]);
            b.hi[d] = std::max(b.hi[d], p[d]);
          }
        }
        return b;
      },
      [](Box a, const Box& b) {
        for (int d = 0; d < 3; ++d) {
          a.lo[d] = std::min(a.lo[d], b.lo[d]);
          a.hi[d] = std::max(a.hi[d], b.hi[d]);
        }
        if (b.bad >= 0 && (a.bad < 0 || b.bad < a.bad)) a.bad = b.bad;
        return a;
      });
  if (box.bad >= 0)
    throw StabilityError("particle row " + std::to_string(box.bad) +
                             " has a non-finite position: the simulation became unstable. Fix: reduce the time "
                             "step or check the contact stiffness and damping");
  axis = {0, 1, 2};
  if (shortest_fastest && n > 0)
    std::stable_sort(axis.begin(), axis.end(),
                     [&](int a, int b) { return box.hi[a] - box.lo[a] < box.hi[b] - box.lo[b]; });
  if (n == 0) {
    origin = {0, 0, 0};
    cell = min_cell;
    dims = {1, 1, 1};
  } else {
    cell = min_cell;
    for (;;) {
      // Counted in double: a row flung far away (a blow-up the stability checks catch after this
      // pass) must grow the cells, not overflow the integer count.
      double total = 1;
      for (int d = 0; d < 3; ++d) total *= std::floor((box.hi[axis[d]] - box.lo[axis[d]]) / cell) + 1;
      if (total <= static_cast<double>(max_cells)) break;
      cell *= 1.26;  // doubles the cell volume every three growths
    }
    for (int d = 0; d < 3; ++d)
      dims[d] = static_cast<std::int64_t>(std::floor((box.hi[axis[d]] - box.lo[axis[d]]) / cell)) + 1;
    for (int d = 0; d < 3; ++d) origin[d] = box.lo[axis[d]];
  }
  const std::size_t ncell = static_cast<std::size_t>(dims[0] * dims[1] * dims[2]);
  cell_of.resize(n);
  const double inv = 1.0 / cell;
  const std::span<const double> c0 = coord[axis[0]], c1 = coord[axis[1]], c2 = coord[axis[2]];
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const auto cx = std::min<std::int64_t>(static_cast<std::int64_t>((c0[i] - origin[0]) * inv), dims[0] - 1);
      const auto cy = std::min<std::int64_t>(static_cast<std::int64_t>((c1[i] - origin[1]) * inv), dims[1] - 1);
      const auto cz = std::min<std::int64_t>(static_cast<std::int64_t>((c2[i] - origin[2]) * inv), dims[2] - 1);
      cell_of[i] = static_cast<std::uint32_t>((cz * dims[1] + cy) * dims[0] + cx);
    }
  });
  start.assign(ncell + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++start[cell_of[i] + 1];
  for (std::size_t c = 0; c < ncell; ++c) start[c + 1] += start[c];
  order.resize(n);
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) order[fill[cell_of[i]]++] = static_cast<std::uint32_t>(i);
}

}  // namespace gf
