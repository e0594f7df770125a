// The uniform cell grid (counting sort): every row lands in the cell its position lies in, rows come
// out in cell order with ties in input order (a stable scatter), the grid is never finer than asked,
// never larger than allowed, and a non-finite coordinate is an error naming the row.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "systems/broadphase/cell_grid.hpp"

using gf::CellGrid;

namespace {

struct Points {
  std::vector<double> x, y, z;
  std::size_t size() const { return x.size(); }
  void add(double a, double b, double c) {
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
  }
};

Points random_points(std::uint64_t seed, std::size_t n, double lo, double hi) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  Points p;
  for (std::size_t i = 0; i < n; ++i) p.add(u(rng), u(rng), u(rng));
  return p;
}

void build(CellGrid& g, const Points& p, double min_cell, std::size_t max_cells = std::size_t(1) << 24) {
  g.build(p.x, p.y, p.z, min_cell, max_cells);
}

// The cell a point belongs to by the grid's own definition: floor((x - origin) / cell) per axis,
// the last cell holding the upper face of the bounding box.
std::array<std::int64_t, 3> expected_cell(const CellGrid& g, double x, double y, double z) {
  const double p[3] = {x, y, z};
  std::array<std::int64_t, 3> c{};
  for (int d = 0; d < 3; ++d) {
    c[d] = static_cast<std::int64_t>((p[d] - g.origin[d]) * (1.0 / g.cell));
    c[d] = std::min(c[d], g.dims[d] - 1);
  }
  return c;
}

// Checks every invariant of a built grid against the points it was built from.
void check_grid(const CellGrid& g, const Points& p, double min_cell, std::size_t max_cells) {
  const std::size_t n = p.size();
  REQUIRE(g.cell >= min_cell);
  REQUIRE(g.cells() == static_cast<std::size_t>(g.dims[0] * g.dims[1] * g.dims[2]));
  REQUIRE(g.cells() <= max_cells);
  REQUIRE(g.cell_of.size() == n);
  REQUIRE(g.order.size() == n);
  REQUIRE(g.start.size() == g.cells() + 1);
  REQUIRE(g.start.front() == 0);
  REQUIRE(g.start.back() == n);

  // Each point lies inside its cell's box (the top cell also holds the bounding box's upper face).
  std::vector<std::size_t> count(g.cells(), 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = expected_cell(g, p.x[i], p.y[i], p.z[i]);
    const auto flat = static_cast<std::uint32_t>((c[2] * g.dims[1] + c[1]) * g.dims[0] + c[0]);
    INFO("row " << i);
    REQUIRE(g.cell_of[i] == flat);
    const double q[3] = {p.x[i], p.y[i], p.z[i]};
    for (int d = 0; d < 3; ++d) {
      REQUIRE(q[d] >= g.origin[d] + static_cast<double>(c[d]) * g.cell);
      if (c[d] < g.dims[d] - 1) REQUIRE(q[d] < g.origin[d] + static_cast<double>(c[d] + 1) * g.cell);
    }
    ++count[flat];
  }
  // start[] is the prefix sum of the per-cell counts.
  for (std::size_t c = 0; c < g.cells(); ++c) REQUIRE(g.start[c + 1] - g.start[c] == count[c]);

  // order is a permutation, in cell order, ties in input order (stable counting sort).
  std::vector<char> seen(n, 0);
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t row = g.order[s];
    REQUIRE(row < n);
    REQUIRE_FALSE(seen[row]);
    seen[row] = 1;
    if (s > 0) {
      const std::uint32_t prev = g.order[s - 1];
      REQUIRE(g.cell_of[prev] <= g.cell_of[row]);
      if (g.cell_of[prev] == g.cell_of[row]) REQUIRE(prev < row);
    }
  }
  for (std::size_t c = 0; c < g.cells(); ++c)
    for (std::uint32_t s = g.start[c]; s < g.start[c + 1]; ++s) REQUIRE(g.cell_of[g.order[s]] == c);
}

}  // namespace

TEST_CASE("cell grid: counting sort bins every point in its cell, in cell order, stable", "[cell_grid]") {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    INFO("seed " << seed);
    const Points p = random_points(seed, 3000, -0.02, 0.05);
    CellGrid g;
    build(g, p, 0.004);
    check_grid(g, p, 0.004, std::size_t(1) << 24);
    // The bounding box spans 7 cm in cells of 4 mm: many cells, several points per cell on average.
    CHECK(g.cell == 0.004);
    CHECK(g.cells() > 1000);
  }
}

TEST_CASE("cell grid: points on cell faces go to the upper cell", "[cell_grid]") {
  // Cell 1.0 from origin 0: integer coordinates are exact faces; 0.5 steps are cell interiors.
  Points p;
  for (int i = 0; i <= 8; ++i)
    for (int j = 0; j <= 2; ++j) p.add(0.5 * i, 1.0 * j, 0.0);
  // Straddling a face by one ulp either side.
  p.add(std::nextafter(2.0, 0.0), 0.0, 0.0);
  p.add(std::nextafter(2.0, 4.0), 0.0, 0.0);
  CellGrid g;
  build(g, p, 1.0);
  check_grid(g, p, 1.0, std::size_t(1) << 24);
  REQUIRE(g.dims[0] == 5);  // 0..4 spans four cells plus the one holding the upper face
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto cx = static_cast<std::int64_t>(g.cell_of[i] % g.dims[0]);
    INFO("x = " << p.x[i]);
    if (p.x[i] == 4.0)
      CHECK(cx == 4);
    else
      CHECK(cx == static_cast<std::int64_t>(std::floor(p.x[i])));
  }
}

TEST_CASE("cell grid: degenerate inputs", "[cell_grid]") {
  SECTION("no points") {
    CellGrid g;
    build(g, Points{}, 0.01);
    CHECK(g.cells() == 1);
    CHECK(g.order.empty());
    CHECK(g.start == std::vector<std::uint32_t>{0, 0});
  }
  SECTION("a single point") {
    Points p;
    p.add(1.0, -2.0, 3.0);
    CellGrid g;
    build(g, p, 0.01);
    check_grid(g, p, 0.01, std::size_t(1) << 24);
    CHECK(g.cells() == 1);
    CHECK(g.order == std::vector<std::uint32_t>{0});
  }
  SECTION("all points at one position") {
    Points p;
    for (int i = 0; i < 17; ++i) p.add(0.25, 0.25, 0.25);
    CellGrid g;
    build(g, p, 0.01);
    check_grid(g, p, 0.01, std::size_t(1) << 24);
    CHECK(g.cells() == 1);
  }
  SECTION("all points inside one cell") {
    const Points p = random_points(7, 200, 0.0, 0.009);
    CellGrid g;
    build(g, p, 0.01);
    check_grid(g, p, 0.01, std::size_t(1) << 24);
    CHECK(g.cells() == 1);
  }
  SECTION("one point flung 1e73 m away (a blow-up, or a corrupt state)") {
    // The cell count was once an integer product of the extents: it overflowed (undefined
    // behaviour, caught by UBSan) instead of growing the cells.
    Points p = random_points(9, 50, 0.0, 0.1);
    p.add(1e73, -1e73, 1e73);
    CellGrid g;
    build(g, p, 0.01, std::size_t(1) << 16);
    check_grid(g, p, 0.01, std::size_t(1) << 16);
    CHECK(g.cells() <= (std::size_t(1) << 16));
  }
  SECTION("a flat layer: one cell thick") {
    Points p = random_points(8, 500, 0.0, 0.1);
    std::fill(p.z.begin(), p.z.end(), 0.5);
    CellGrid g;
    build(g, p, 0.01);
    check_grid(g, p, 0.01, std::size_t(1) << 24);
    CHECK(g.dims[2] == 1);
  }
}

TEST_CASE("cell grid: a sparse domain coarsens the cells instead of exceeding max_cells", "[cell_grid]") {
  // Two clusters 1 km apart with 1 mm cells would need 1e18 cells; the edge must grow to fit.
  Points p = random_points(11, 100, 0.0, 0.01);
  const Points far = random_points(12, 100, 1000.0, 1000.01);
  for (std::size_t i = 0; i < far.size(); ++i) p.add(far.x[i], far.y[i], far.z[i]);
  const std::size_t max_cells = 4096;
  CellGrid g;
  build(g, p, 0.001, max_cells);
  check_grid(g, p, 0.001, max_cells);
  CHECK(g.cell > 0.001);
}

TEST_CASE("cell grid: a non-finite coordinate is an error naming the row", "[cell_grid]") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Points p = random_points(3, 20000, 0.0, 1.0);  // several parallel blocks of the bounding-box reduction
  SECTION("NaN in y") {
    p.y[1234] = nan;
    CellGrid g;
    REQUIRE_THROWS_WITH(build(g, p, 0.01), Catch::Contains("particle row 1234 ") && Catch::Contains("non-finite"));
  }
  SECTION("infinity in z") {
    p.z[19999] = -inf;
    CellGrid g;
    REQUIRE_THROWS_WITH(build(g, p, 0.01), Catch::Contains("particle row 19999 "));
  }
  SECTION("several bad rows: the first is named, whatever the thread schedule") {
    p.x[17000] = nan;
    p.x[9000] = inf;
    p.z[15] = nan;
    CellGrid g;
    REQUIRE_THROWS_WITH(build(g, p, 0.01), Catch::Contains("particle row 15 "));
  }
}
