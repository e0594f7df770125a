// Lacey's mixing index and the drum's radial and depth segregation indices (systems/analysis/mixing.hpp) on
// synthetic beds whose mixing is known by construction: grains on a cubic lattice of 1 mm pitch,
// labelled by their place (segregated) or at random with a fixed seed (mixed). The lattice keeps
// the number of grains per cell fixed, so the statistics of a random bed are those of binomial
// draws in equal cells, and every tolerance below follows from them. Then the scene's [analysis]
// keys, and the measures' columns in series.csv and keys in summary.json, through resumed runs.
#include "systems/analysis/mixing.hpp"

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <nlohmann/json.hpp>

#include "systems/analysis/metrics.hpp"
#include "systems/analysis/pattern.hpp"
#include "systems/setup/dem_scene.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kPitch = 1e-3;  // m, lattice spacing
constexpr std::int32_t kA = 1, kB = 0;

struct Grain {
  double x, y, z, r;
  std::int32_t type;
};

// A Grains table holding `list` in order, ids 0 .. n-1 (the measures read positions, radii, species
// and ids only).
gf::Grains table_of(const std::vector<Grain>& list) {
  gf::Grains g;
  g.resize(list.size());
  for (std::size_t i = 0; i < list.size(); ++i) {
    g.pos.x[i] = list[i].x;
    g.pos.y[i] = list[i].y;
    g.pos.z[i] = list[i].z;
    g.vel.x[i] = g.vel.y[i] = g.vel.z[i] = 0.0;
    g.radius.r[i] = list[i].r;
    g.species.type[i] = list[i].type;
    g.pid.id[i] = static_cast<std::int64_t>(i);
  }
  g.next_id = static_cast<std::int64_t>(list.size());
  return g;
}

// k^3 grains at the centres of a cubic lattice filling [0, k mm]^3; `label(x, y, z)` gives each
// grain's species, and species A has radius ra, B radius rb.
std::vector<Grain> lattice_box(int k, double ra, double rb, const std::function<std::int32_t(double, double, double)>& label) {
  std::vector<Grain> out;
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j)
      for (int l = 0; l < k; ++l) {
        const double x = (i + 0.5) * kPitch, y = (j + 0.5) * kPitch, z = (l + 0.5) * kPitch;
        const std::int32_t t = label(x, y, z);
        out.push_back({x, y, z, t == kA ? ra : rb, t});
      }
  return out;
}

// Labels drawn independently, A with probability q, in lattice order from a fixed seed.
std::function<std::int32_t(double, double, double)> random_labels(double q, std::uint64_t seed) {
  auto rng = std::make_shared<std::mt19937_64>(seed);
  return [rng, q](double, double, double) {
    return std::uniform_real_distribution<double>(0.0, 1.0)(*rng) < q ? kA : kB;
  };
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
// Lacey's index

TEST_CASE("lacey: a bed segregated along cell faces gives 0", "[mixing]") {
  // 40^3 grains, A (1 mm) in x < 20 mm and B (0.7 mm) beyond, 4 mm cells: the interface is a cell
  // face, so every cell holds one species and s^2 = p (1 - p) = s0^2 up to rounding.
  const auto g = table_of(lattice_box(40, 0.5e-3, 0.35e-3, [](double x, double, double) { return x < 0.02 ? kA : kB; }));
  const gf::LaceyIndex m = gf::lacey_index(g, kA, 4e-3);
  CHECK(m.cells == 1000);
  CHECK(m.grains_per_cell == 64.0);
  CHECK(m.cell == 4e-3);
  // p = vA / (vA + vB), the grains per side being equal.
  CHECK(m.fraction_a == Approx(1.0 / (1.0 + 0.7 * 0.7 * 0.7)).epsilon(1e-12));
  CHECK(m.variance == Approx(m.segregated).epsilon(1e-12));
  CHECK(std::abs(m.index) < 1e-12);
  CHECK(m.random > 0.0);
  CHECK(m.random < 0.1 * m.segregated);
}

TEST_CASE("lacey: a bed segregated across the cells stays close to 0", "[mixing]") {
  // 39^3 grains, A in x < 20 mm, 3 mm cells: 13^3 full cells of 27 grains, all counted. The
  // interface cuts the layer of cells from 18 to 21 mm, which mixes two columns of A with one of B.
  // Only those cells move towards p, each taking at most p (1 - p) off s^2, so
  // M <= share / (1 - sr^2 / s0^2), share = that layer's solid volume = (2 vA + vB) / (20 vA + 19 vB)
  // = 0.088 and sr^2 / s0^2 = 0.028: M < 0.1.
  const auto g = table_of(lattice_box(39, 0.5e-3, 0.35e-3, [](double x, double, double) { return x < 0.02 ? kA : kB; }));
  const gf::LaceyIndex m = gf::lacey_index(g, kA, 3e-3);
  CHECK(m.cells == 13 * 13 * 13);
  CHECK(m.grains_per_cell == 27.0);
  INFO("M = " << m.index << ", sr^2 / s0^2 = " << m.random / m.segregated);
  CHECK(m.index > 0.0);
  CHECK(m.index < 0.1);
}

TEST_CASE("lacey: a random bed of one size gives 1", "[mixing]") {
  // 40^3 grains of one size labelled A with probability 1/2, 4 mm cells: 1000 cells of 64 grains.
  // A cell's fraction is binomial, so E[s^2] = p (1 - p) / 64 = sr^2 exactly; s^2 averages 1000
  // nearly normal squares, so its relative spread is sqrt(2 / 1000) = 0.045, and 4 of it bounds
  // |s^2 / sr^2 - 1| for all but 1e-4 of seeds. M - 1 = (sr^2 - s^2) / (s0^2 - sr^2) is that
  // deviation times sr^2 / (s0^2 - sr^2) = 1/63.
  const auto g = table_of(lattice_box(40, 0.5e-3, 0.5e-3, random_labels(0.5, 2024)));
  const gf::LaceyIndex m = gf::lacey_index(g, kA, 4e-3);
  REQUIRE(m.cells == 1000);
  CHECK(m.grains_per_cell == 64.0);
  CHECK(m.random == Approx(m.segregated / 64.0).epsilon(1e-12));
  const double spread = 4.0 * std::sqrt(2.0 / 1000.0);
  INFO("s^2 / sr^2 = " << m.variance / m.random << ", M = " << m.index);
  CHECK(std::abs(m.variance / m.random - 1.0) < spread);
  CHECK(std::abs(m.index - 1.0) < spread / 63.0);
}

TEST_CASE("lacey: a random bed of two sizes gives 1 with the size-corrected random variance", "[mixing]") {
  // 50^3 grains, A of 1 mm drawn with probability 1/9, B of 0.5 mm: equal volumes on average
  // (p = 1/2), 5 mm cells: 1000 cells of 125 grains. Summing the binomial law of A per cell
  // exactly gives E[s^2] / sr^2 = 1.012 (the large-count form's bias at 125 grains); the spread
  // of s^2 is sqrt(2 / 1000) = 0.045 relative as above (the binomial's fourth moment is within 2 %
  // of a normal's here), so |s^2 / sr^2 - 1| < 0.012 + 4 * 0.045. Lacey's one-size form
  // p (1 - p) / 125 would put the ratio at 2.56: the same bed would read as less than random.
  const auto g = table_of(lattice_box(50, 0.5e-3, 0.25e-3, random_labels(1.0 / 9.0, 7)));
  const gf::LaceyIndex m = gf::lacey_index(g, kA, 5e-3);
  REQUIRE(m.cells == 1000);
  CHECK(m.grains_per_cell == 125.0);
  const double ratio = m.variance / m.random;
  const double one_size = m.variance / (m.segregated / m.grains_per_cell);
  INFO("p = " << m.fraction_a << ", s^2 / sr^2 = " << ratio << ", s^2 / (p (1 - p) / n) = " << one_size
              << ", M = " << m.index);
  CHECK(m.fraction_a == Approx(0.5).margin(0.02));
  CHECK(std::abs(ratio - 1.0) < 0.012 + 4.0 * std::sqrt(2.0 / 1000.0));
  CHECK(one_size > 2.0);
  // sr^2 / s0^2 = [(1 - p) vA + p vB] / (125 mean v) = 0.020, so sr^2 / (s0^2 - sr^2) = 0.021 and
  // M is within 0.2 * 0.021 of 1.
  CHECK(std::abs(m.index - 1.0) < 0.2 * 0.021);
}

TEST_CASE("lacey: cells with fewer grains than the minimum are left out", "[mixing]") {
  // 3 mm cells on a 40 mm box: 13 full layers of cells per axis (27 grains each) and a last layer
  // one grain thick (9, 3 or 1 grains), which the default minimum of 10 leaves out.
  const auto g = table_of(lattice_box(40, 0.5e-3, 0.5e-3, random_labels(0.5, 11)));
  const gf::LaceyIndex counted = gf::lacey_index(g, kA, 3e-3);
  CHECK(counted.cells == 13 * 13 * 13);
  CHECK(counted.grains_per_cell == 27.0);
  const gf::LaceyIndex all = gf::lacey_index(g, kA, 3e-3, 1);
  CHECK(all.cells == 14 * 14 * 14);
  CHECK(all.grains_per_cell == Approx(64000.0 / (14 * 14 * 14)).epsilon(1e-12));
}

TEST_CASE("lacey: the spread is the one Danckwerts' index reads", "[mixing]") {
  // One binning and one weighted spread serve both: I^2 = s^2 / s0^2 at the same cells.
  const auto g = table_of(lattice_box(30, 0.5e-3, 0.3e-3, [](double x, double y, double) {
    return x + 0.5 * y < 0.02 ? kA : kB;
  }));
  const gf::LaceyIndex m = gf::lacey_index(g, kA, 3e-3);
  const double i = gf::segregation_index(g, kA, 3e-3, 10);
  CHECK(i * i == Approx(m.variance / m.segregated).epsilon(1e-12));
  CHECK(m.index > 0.0);
  CHECK(m.index < 1.0);
}

TEST_CASE("lacey: the index does not depend on the order of the rows", "[mixing]") {
  // Cells are summed in the order of their key, not a hash map's; within a cell the order of the
  // rows changes only the last bits of the sums.
  auto list = lattice_box(30, 0.5e-3, 0.3e-3, random_labels(0.4, 5));
  const gf::LaceyIndex a = gf::lacey_index(table_of(list), kA, 3e-3);
  std::reverse(list.begin(), list.end());
  const gf::LaceyIndex b = gf::lacey_index(table_of(list), kA, 3e-3);
  CHECK(a.cells == b.cells);
  CHECK(a.index == Approx(b.index).epsilon(1e-12));
}

TEST_CASE("lacey: one species, no counted cell or a bad cell edge", "[mixing]") {
  const auto g = table_of(lattice_box(10, 0.5e-3, 0.5e-3, [](double, double, double) { return kB; }));
  const gf::LaceyIndex none = gf::lacey_index(g, kA, 3e-3);
  CHECK(std::isnan(none.index));
  CHECK(none.fraction_a == 0.0);
  // 100 mm cells: the whole 10 mm bed falls in one cell, with p = 1/2 there; sr^2 = s0^2 / 1000.
  const auto half = table_of(lattice_box(10, 0.5e-3, 0.5e-3, [](double x, double, double) { return x < 0.005 ? kA : kB; }));
  const gf::LaceyIndex one = gf::lacey_index(half, kA, 0.1);
  CHECK(one.cells == 1);
  CHECK(one.index == Approx(1000.0 / 999.0).epsilon(1e-12));  // s^2 = 0: more even than random
  CHECK(std::isnan(gf::lacey_index(half, kA, 1e-3, 2).index));  // 1 grain per cell: none counted
  CHECK_THROWS_AS(gf::lacey_index(half, kA, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::lacey_index(half, kA, std::numeric_limits<double>::infinity()), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------------------------
// Radial segregation in a drum's cross-section

namespace {

constexpr double kR = 0.05;  // m, drum radius

gf::DrumSection drum_z() { return gf::test::drum_section_z(kR); }

// A bed filling the lower half of the drum: 1 mm grains on the lattice inside radius R - 1 mm and
// below the axis, three layers deep along the axis (about 11,300 grains). `label(rho)` gives each
// grain's species from its distance to the half disc's centroid in the section plane.
std::vector<Grain> half_drum(const std::function<std::int32_t(double)>& label) {
  std::vector<Grain> out;
  double sx = 0.0, sy = 0.0;
  const int k = static_cast<int>(kR / kPitch);
  for (int i = -k; i < k; ++i)
    for (int j = -k; j < 0; ++j) {
      const double x = (i + 0.5) * kPitch, y = (j + 0.5) * kPitch;
      if (x * x + y * y > (kR - kPitch) * (kR - kPitch)) continue;
      for (int l = -1; l <= 1; ++l) out.push_back({x, y, l * kPitch, 0.5e-3, kB});
      sx += 3 * x;
      sy += 3 * y;
    }
  const double cx = sx / static_cast<double>(out.size()), cy = sy / static_cast<double>(out.size());
  for (Grain& g : out) g.type = label(std::hypot(g.x - cx, g.y - cy));
  return out;
}

}  // namespace

TEST_CASE("radial segregation: A only in the core gives -1", "[mixing]") {
  // A within 0.3 R of the centroid, a disc inside the bed (the centroid is 4 R / (3 pi) = 0.42 R
  // below the axis) of about a fifth of its area, well inside the half-volume core (the split
  // radius is about 0.5 R): the periphery holds no A, so the index is -1 exactly.
  const auto g = table_of(half_drum([](double rho) { return rho < 0.3 * kR ? kA : kB; }));
  const gf::RadialSegregation s = gf::radial_segregation(g, kA, drum_z());
  REQUIRE(s.split_radius > 0.3 * kR);
  CHECK(s.split_radius < 0.6 * kR);
  CHECK(s.centre_u == Approx(0.0).margin(1e-12));
  // The lattice's half disc of radius R - 1 mm: its centroid to within half a pitch.
  CHECK(s.centre_v == Approx(-4.0 * (kR - kPitch) / (3.0 * std::numbers::pi)).margin(0.5 * kPitch));
  CHECK(s.periphery_fraction == 0.0);
  CHECK(s.core_fraction > 0.3);
  CHECK(s.index == -1.0);
}

TEST_CASE("radial segregation: A only at the periphery gives +1", "[mixing]") {
  const auto g = table_of(half_drum([](double rho) { return rho > 0.75 * kR ? kA : kB; }));
  const gf::RadialSegregation s = gf::radial_segregation(g, kA, drum_z());
  REQUIRE(s.split_radius < 0.75 * kR);
  CHECK(s.core_fraction == 0.0);
  CHECK(s.periphery_fraction > 0.0);
  CHECK(s.index == 1.0);
}

TEST_CASE("radial segregation: a random bed gives about 0", "[mixing]") {
  // Labels drawn with probability q = 0.3. Core and periphery each hold N / 2 grains of one size,
  // so their fractions are independent with variance q (1 - q) / (N / 2), and the index is
  // (phi_p - phi_c) / (2 q) to first order: its standard deviation is sqrt((1 - q) / (N q)),
  // 0.014 for N = 11,300. 4 of it bounds the index for all but 1e-4 of seeds.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double q = 0.3;
  const auto g = table_of(half_drum([&](double) { return u(rng) < q ? kA : kB; }));
  const gf::RadialSegregation s = gf::radial_segregation(g, kA, drum_z());
  const double n = static_cast<double>(g.n_owned);
  const double sigma = std::sqrt((1.0 - q) / (n * q));
  INFO("index " << s.index << ", core " << s.core_fraction << ", periphery " << s.periphery_fraction << ", sigma "
                << sigma);
  CHECK(std::abs(s.index) < 4.0 * sigma);
}

TEST_CASE("radial segregation: the section ignores the axial coordinate", "[mixing]") {
  // The drum's frame does not depend on where along the axis a grain is: moving every A grain
  // along the axis leaves the index as it was, and the axis may point any way.
  auto list = half_drum([](double rho) { return rho > 0.6 * kR ? kA : kB; });
  const gf::RadialSegregation before = gf::radial_segregation(table_of(list), kA, drum_z());
  for (Grain& g : list)
    if (g.type == kA) g.z += 0.004;
  const gf::RadialSegregation after = gf::radial_segregation(table_of(list), kA, drum_z());
  CHECK(after.index == before.index);
  // The same bed with the drum's axis along x and gravity along -y: the section is (z, y).
  for (Grain& g : list) std::swap(g.x, g.z);
  gf::Wall w;
  w.kind = gf::Wall::Kind::CylinderInner;
  w.cur_center = {0, 0, 0};
  w.cur_axis = {1, 0, 0};
  w.radius = kR;
  const gf::RadialSegregation turned = gf::radial_segregation(table_of(list), kA, gf::drum_section(w, {0, -9.81, 0}));
  CHECK(turned.index == Approx(before.index).margin(1e-12));
  CHECK(before.index > 0.5);
}

TEST_CASE("radial segregation: undefined without species A or without a periphery", "[mixing]") {
  const auto none = table_of(half_drum([](double) { return kB; }));
  CHECK(std::isnan(gf::radial_segregation(none, kA, drum_z()).index));
  const auto single = table_of({{0.0, -0.02, 0.0, 0.5e-3, kA}});
  const gf::RadialSegregation one = gf::radial_segregation(single, kA, drum_z());
  CHECK(one.core_fraction == 1.0);
  CHECK(std::isnan(one.index));
  CHECK(std::isnan(gf::radial_segregation(gf::Grains{}, kA, drum_z()).index));
}

// ---------------------------------------------------------------------------------------------------------------------
// Depth segregation against the free surface

namespace {

// The half-drum lattice labelled by place: `label(x, y)`. Its free surface is flat at y = 0 (the
// top row's centres at -0.5 mm, radius 0.5 mm). The deepest half of its area lies below
// h = 0.404 R (the circular segment below y = -h has area R^2 acos(h/R) - h sqrt(R^2 - h^2), a
// quarter of pi R^2 there), so the split falls near y = -0.40 R on the lattice too.
std::vector<Grain> half_drum_xy(const std::function<std::int32_t(double, double)>& label) {
  auto out = half_drum([](double) { return kB; });
  for (Grain& g : out) g.type = label(g.x, g.y);
  return out;
}

// The pattern classifier's fit of the surface (pattern.hpp), as the series feeds it to the index.
gf::DepthSegregation depth_of(const std::vector<Grain>& list, const gf::DrumSection& drum) {
  const gf::Grains g = table_of(list);
  const std::size_t n = g.n_owned;
  const gf::PatternGrains pg{{g.pos.x.data(), n}, {g.pos.y.data(), n}, {g.pos.z.data(), n},
                             {g.radius.r.data(), n}, {g.species.type.data(), n}};
  const gf::Pattern p = gf::classify_pattern(pg, drum);
  return gf::depth_segregation(g, kA, drum, p.surface_angle, p.surface_level);
}

}  // namespace

TEST_CASE("depth segregation: layers under a flat surface give +1 and -1", "[mixing]") {
  // The fitted surface of the lattice is the line v = 0 (every column's top is at 0).
  const auto flat = table_of(half_drum_xy([](double, double) { return kB; }));
  const std::size_t n = flat.n_owned;
  const gf::Pattern p = gf::classify_pattern({{flat.pos.x.data(), n}, {flat.pos.y.data(), n}, {flat.pos.z.data(), n},
                                              {flat.radius.r.data(), n}, {flat.species.type.data(), n}},
                                             drum_z());
  CHECK(p.surface_angle == Approx(0.0).margin(1e-12));
  CHECK(p.surface_level == Approx(0.0).margin(1e-12));
  // A below 0.5 R lies inside the deep half: the shallow half holds none.
  const gf::DepthSegregation deep = depth_of(half_drum_xy([](double, double y) { return y < -0.5 * kR ? kA : kB; }),
                                             drum_z());
  CHECK(deep.split_depth == Approx(0.404 * kR).margin(2.0 * kPitch));
  CHECK(deep.shallow_fraction == 0.0);
  CHECK(deep.index == 1.0);
  // A above 0.3 R of depth lies inside the shallow half.
  const gf::DepthSegregation top = depth_of(half_drum_xy([](double, double y) { return y > -0.3 * kR ? kA : kB; }),
                                            drum_z());
  CHECK(top.deep_fraction == 0.0);
  CHECK(top.index == -1.0);
}

TEST_CASE("depth segregation: a tilted surface is measured across its own slope", "[mixing]") {
  // The bed and its layers turned by 20 degrees about the axis (a rolling bed's slope): depth is
  // taken perpendicular to the fitted line, so A deep under the tilted surface still gives +1.
  // Read against a horizontal line instead, the same layers cross the split and give less.
  const double a = 20.0 * std::numbers::pi / 180.0, c = std::cos(a), s = std::sin(a);
  auto list = half_drum_xy([](double, double y) { return y < -0.5 * kR ? kA : kB; });
  for (Grain& g : list) {
    const double x = g.x, y = g.y;
    g.x = c * x - s * y;
    g.y = s * x + c * y;
  }
  const gf::Grains g = table_of(list);
  const gf::DepthSegregation along = gf::depth_segregation(g, kA, drum_z(), a, 0.0);
  CHECK(along.index == 1.0);
  const gf::DepthSegregation level = gf::depth_segregation(g, kA, drum_z(), 0.0, 0.0);
  CHECK(level.index < 0.9);
  // The fit of the turned lattice's top finds that slope to within a degree (its columns are 2 mm
  // wide; the lattice's turned steps are a pitch high).
  const gf::DepthSegregation fitted = depth_of(list, drum_z());
  CHECK(fitted.index == 1.0);
}

TEST_CASE("depth segregation: a core reads near 0 where the radial index reads -1", "[mixing]") {
  // A within 0.3 R of the centroid (0.42 R deep): the depth split (0.40 R) cuts that disc near its
  // middle, about 54 % of its area below, so the index is (0.54 - 0.46) / 1 = 0.08 to first
  // order; 0.15 bounds it with the lattice's steps. The radial index of the same bed is -1: the
  // two indices tell a core from layers.
  const auto core = half_drum([](double rho) { return rho < 0.3 * kR ? kA : kB; });
  const gf::DepthSegregation d = depth_of(core, drum_z());
  CHECK(std::abs(d.index) < 0.15);
  CHECK(gf::radial_segregation(table_of(core), kA, drum_z()).index == -1.0);
}

TEST_CASE("depth segregation: a random bed gives about 0, and no surface gives NaN", "[mixing]") {
  // As for the radial index: halves of N / 2 grains of one size, sigma = sqrt((1 - q) / (N q)).
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double q = 0.3;
  const auto list = half_drum([&](double) { return u(rng) < q ? kA : kB; });
  const gf::DepthSegregation d = depth_of(list, drum_z());
  const double sigma = std::sqrt((1.0 - q) / (static_cast<double>(list.size()) * q));
  INFO("index " << d.index << ", sigma " << sigma);
  CHECK(std::abs(d.index) < 4.0 * sigma);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK(std::isnan(gf::depth_segregation(table_of(list), kA, drum_z(), nan, 0.0).index));
  CHECK(std::isnan(gf::depth_segregation(table_of(list), kA, drum_z(), 0.0, nan).index));
  CHECK(std::isnan(depth_of(half_drum([](double) { return kB; }), drum_z()).index));
}

// ---------------------------------------------------------------------------------------------------------------------
// Seed 004's inhomogeneity coefficient Vc of a transverse layer

TEST_CASE("layer mixing: a layer split between the species gives Vc = sqrt((1 - c) / c) and Lacey 0", "[mixing]") {
  // 40^3 grains of one size, A where y < 12 mm (30 %), the axis along x: the layer at x = 20 mm,
  // 2 mm thick, holds two lattice planes; 4 mm cells in the (y, z) plane, aligned with the inlet,
  // meet the interface on a cell face, so every cell holds one species and s^2 = c (1 - c) exactly.
  const auto g =
      table_of(lattice_box(40, 0.5e-3, 0.5e-3, [](double, double y, double) { return y < 0.012 ? kA : kB; }));
  const gf::LayerMixing m = gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, 4e-3);
  CHECK(m.cells == 100);
  CHECK(m.grains_per_cell == 32.0);
  CHECK(m.fraction_a == Approx(0.3).epsilon(1e-12));
  CHECK(m.vc == Approx(std::sqrt(0.7 / 0.3)).epsilon(1e-12));
  CHECK(std::abs(m.lacey) < 1e-12);
}

TEST_CASE("layer mixing: a random layer gives Vc near its binomial floor and Lacey near 1", "[mixing]") {
  // Labels at random with q = 0.3 in one size: s^2 of the cells is q (1 - q) / n in expectation,
  // n = 32 grains per cell, so Vc = sqrt((1 - q) / (q n)) = 0.27 in expectation; over 100 cells the
  // spread of s^2 is sqrt(2 / 99) of it (chi-square), 14 %: Vc within 30 % of that floor holds at
  // over 4 standard deviations of s^2 (Vc moves half as much as s^2). Lacey's index within 0.3 of 1
  // is the same bound.
  const auto g = table_of(lattice_box(40, 0.5e-3, 0.5e-3, random_labels(0.3, 11)));
  const gf::LayerMixing m = gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, 4e-3);
  const double floor_vc = std::sqrt((1.0 - m.fraction_a) / (m.fraction_a * m.grains_per_cell));
  INFO("Vc " << m.vc << ", binomial floor " << floor_vc << ", Lacey " << m.lacey << ", c " << m.fraction_a);
  CHECK(m.vc == Approx(floor_vc).epsilon(0.3));
  CHECK(m.lacey == Approx(1.0).margin(0.3));
}

TEST_CASE("layer mixing: only the layer counts, and its frame follows the axis", "[mixing]") {
  // A everywhere outside the slab 18-22 mm along x, mixed in it: the layer at 20 mm sees only
  // its own grains. The same bed read along -x from the far end gives the same numbers.
  auto label = random_labels(0.5, 3);
  const auto list = lattice_box(40, 0.5e-3, 0.5e-3, [&](double x, double y, double z) {
    const std::int32_t t = label(x, y, z);
    return std::abs(x - 0.02) <= 2e-3 ? t : kA;
  });
  const gf::Grains g = table_of(list);
  const gf::LayerMixing m = gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, 4e-3);
  CHECK(m.fraction_a < 0.7);
  const gf::LayerMixing back = gf::layer_mixing(g, kA, {0.04, 0, 0}, {-2.0, 0, 0}, 0.02, 2e-3, 4e-3);
  CHECK(back.grains == m.grains);
  CHECK(back.fraction_a == Approx(m.fraction_a).epsilon(1e-12));
  // Cells of one species only in the layer: NaN Lacey (c = 1), Vc = 0.
  const gf::LayerMixing pure = gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.035, 2e-3, 4e-3);
  CHECK(pure.fraction_a == 1.0);
  CHECK(pure.vc == 0.0);
  CHECK(std::isnan(pure.lacey));
  // An empty layer, and bad arguments.
  CHECK(std::isnan(gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 1.0, 2e-3, 4e-3).vc));
  CHECK_THROWS_AS(gf::layer_mixing(g, kA, {0, 0, 0}, {0, 0, 0}, 0.02, 2e-3, 4e-3), std::invalid_argument);
  CHECK_THROWS_AS(gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.02, 0.0, 4e-3), std::invalid_argument);
  CHECK_THROWS_AS(gf::layer_mixing(g, kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, -1.0), std::invalid_argument);
}

TEST_CASE("layer mixing: pooled samples count as one sample of all their grains, and lower the binomial floor",
          "[mixing]") {
  // Four samples of the same lattice with independent random labels (q = 0.5): pooling their cells
  // must give exactly what one table holding all four samples' grains gives (the sums per cell are
  // the same sums), and Vc falls to the floor of four times the grains per cell, sqrt((1 - q) / (q 4n)),
  // within the 30 % of the single-sample test above.
  gf::LayerCells pooled;
  std::vector<Grain> all;
  for (std::uint64_t seed = 21; seed < 25; ++seed) {
    const auto list = lattice_box(40, 0.5e-3, 0.5e-3, random_labels(0.5, seed));
    pooled.add(gf::layer_cells(table_of(list), kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, 4e-3));
    all.insert(all.end(), list.begin(), list.end());
  }
  const gf::LayerMixing p = gf::layer_quality(pooled, 10);
  const gf::LayerMixing u = gf::layer_mixing(table_of(all), kA, {0, 0, 0}, {1, 0, 0}, 0.02, 2e-3, 4e-3, 10);
  CHECK(p.cells == u.cells);
  CHECK(p.grains == u.grains);
  CHECK(p.grains_per_cell == 128.0);
  CHECK(p.vc == Approx(u.vc).epsilon(1e-12));
  CHECK(p.lacey == Approx(u.lacey).epsilon(1e-12));
  const double floor_vc = std::sqrt((1.0 - p.fraction_a) / (p.fraction_a * p.grains_per_cell));
  INFO("pooled Vc " << p.vc << ", binomial floor " << floor_vc);
  CHECK(p.vc == Approx(floor_vc).epsilon(0.3));
}

// ---------------------------------------------------------------------------------------------------------------------
// The scene's [analysis] keys, and the measures in series.csv and summary.json

namespace {

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gf::test::quote;
using gf::test::run_cli;
using gf::test::TempDir;

// The small drum of test_support.hpp: 1 and 3 mm grains, so the default cell is 9 mm.
const std::string kDrum = gf::test::small_drum_scene(60.0, "max_overlap = 0.3\n");

std::string load_error(const std::string& text) {
  try {
    gf::load_dem_scene(gf::SceneDoc::parse(text, "drum.toml"));
  } catch (const gf::SceneError& e) {
    return e.what();
  }
  return "";
}

// The drum with its large species taken out: one species.
std::string one_species(std::string text) {
  for (const std::string cut : {"[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n", ", large = 20"})
    text.erase(text.find(cut), cut.size());
  return text;
}

}  // namespace

TEST_CASE("mixing scene keys: [analysis] sets the cells of a binary mixture, checked against its grains",
          "[mixing][scene]") {
  const gf::DemScene plain = gf::load_dem_scene(gf::SceneDoc::parse(kDrum, "drum.toml"));
  CHECK(plain.mixing_cell == Approx(9e-3).epsilon(1e-12));  // three large diameters
  CHECK(plain.mixing_min_grains == 10);
  const gf::DemScene set =
      gf::load_dem_scene(gf::SceneDoc::parse(kDrum + "[analysis]\nmixing_cell = 0.006\nmixing_min_grains = 20\n", "drum.toml"));
  CHECK(set.mixing_cell == 0.006);
  CHECK(set.mixing_min_grains == 20);
  CHECK(gf::load_dem_scene(gf::SceneDoc::parse(one_species(kDrum), "drum.toml")).mixing_cell == 0.0);

  const std::string narrow = load_error(kDrum + "[analysis]\nmixing_cell = 0.002\n");
  CHECK_THAT(narrow, Contains("analysis.mixing_cell") && Contains("give at least 0.003 m"));
  CHECK_THAT(load_error(kDrum + "[analysis]\nmixing_cell = -1.0\n"), Contains("analysis.mixing_cell"));
  CHECK_THAT(load_error(kDrum + "[analysis]\nmixing_min_grains = 1\n"), Contains("analysis.mixing_min_grains"));
  CHECK_THAT(load_error(kDrum + "[analysis]\nmixing_cel = 0.006\n"), Contains("mixing_cel") && Contains("mixing_cell"));
  const std::string single = load_error(one_species(kDrum) + "[analysis]\nmixing_cell = 0.006\n");
  CHECK_THAT(single, Contains("analysis") && Contains("two species") && Contains("remove the [analysis] table"));
}

TEST_CASE("mixing outputs: series.csv and summary.json carry the measures, and a resumed run writes the same rows",
          "[mixing][cli]") {
  TempDir dir("mixing_cli");
  const fs::path scene = dir.write("drum.toml", kDrum + "[analysis]\nmixing_cell = 0.006\n");
  const auto args = [&](const fs::path& out, const std::string& more) {
    return "run " + quote(scene.string()) + " --out " + quote(out.string()) +
           " --threads 1 --quiet --set output.checkpoint_interval=4e-3 " + more;
  };
  const fs::path one = dir.path / "one", two = dir.path / "two";
  REQUIRE(run_cli(dir, args(one, "--steps 1300")).code == 0);
  // The first piece stops off the series grid, so its final row is one the resumed piece drops.
  REQUIRE(run_cli(dir, args(two, "--steps 550")).code == 0);
  const auto resumed =
      run_cli(dir, args(two, "--steps 1300 --resume " + quote((two / "checkpoints" / "checkpoint.gfc").string())));
  INFO(resumed.err);
  REQUIRE(resumed.code == 0);
  const auto rows = gf::test::read_lines(one / "series.csv");
  REQUIRE(rows.size() == 1 + 14);
  CHECK(rows[0] ==
        "time,angle,ke_translational,ke_rotational,contacts,wall_contacts,max_overlap_ratio,segregation_index,"
        "lacey_index,lacey_cell_grains,pattern,petals,pattern_contrast,surface_angle,radial_segregation,"
        "depth_segregation");
  CHECK(gf::test::read_file(two / "series.csv") == gf::test::read_file(one / "series.csv"));

  const auto final_values = nlohmann::json::parse(gf::test::read_file(one / "summary.json")).at("final");
  CHECK(final_values.at("lacey_cell") == 0.006);
  CHECK(final_values.contains("lacey_index"));
  CHECK(final_values.at("lacey_cell_grains").get<double>() >= 0.0);
  const double radial = final_values.at("radial_segregation").get<double>();
  CHECK(std::abs(radial) <= 1.0);
  const double depth = final_values.at("depth_segregation").get<double>();
  CHECK(std::abs(depth) <= 1.0);
}

TEST_CASE("mixing outputs: a binary mixture without a drum has Lacey's columns and no radial one", "[mixing][cli]") {
  TempDir dir("mixing_box");
  const fs::path scene =
      dir.write("box.toml", gf::test::binary_box_scene(200, 10) + "[output]\nseries_interval = 1.0e-4\n");
  REQUIRE(run_cli(dir, "run " + quote(scene.string()) + " --out " + quote((dir.path / "out").string()) +
                           " --threads 1 --quiet --steps 20")
              .code == 0);
  const auto rows = gf::test::read_lines(dir.path / "out" / "series.csv");
  REQUIRE(rows.size() > 1);
  CHECK(rows[0].ends_with(",segregation_index,lacey_index,lacey_cell_grains"));
  const auto final_values = nlohmann::json::parse(gf::test::read_file(dir.path / "out" / "summary.json")).at("final");
  CHECK(final_values.at("lacey_cell") == Approx(9e-3).epsilon(1e-12));
  CHECK_FALSE(final_values.contains("radial_segregation"));
}
