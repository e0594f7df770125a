// The angle of repose (systems/analysis/repose.hpp) on synthetic heaps whose slope is known by
// construction: 1 mm grains (radius 0.5 mm) on a cubic lattice of pitch p = 1 mm, kept where their
// centre lies under the heap's surface. A column's surface is then the top of the highest lattice
// level under the surface: a staircase, below the true surface (shifted by the radius) by an error
// e in [0, p). A constant error leaves the fitted slope unchanged; the largest slope error a least-
// squares line over a span L can take from errors confined to a band of width p is that of a step
// of p at the span's middle, 0.75 p / L (the slope of a step against uniformly spaced columns:
// cov(s, e) / var(s) = (p L / 16) / (L^2 / 12)). So each fit is checked against
// |tan(measured) - tan(true)| <= 0.75 p / L, L the span of the columns it fitted: a bound that
// holds whatever the staircase's phase, and is 1 to 2 degrees at the spans here.
#include "systems/analysis/repose.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

constexpr double kPitch = 1e-3, kR = 0.5e-3;
constexpr double kDeg = std::numbers::pi / 180.0;

struct Pack {
  std::vector<double> x, y, z, r;
  void add(double px, double py, double pz) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
    r.push_back(kR);
  }
  gf::ReposeGrains view() const { return {x, y, z, r}; }
};

// Lattice points (x, y, z), y up, in the box |x|, |z| <= half, 0 <= y, kept where keep(x, y, z).
Pack lattice(double half, double height, const std::function<bool(double, double, double)>& keep) {
  Pack p;
  const int n = static_cast<int>(half / kPitch), m = static_cast<int>(height / kPitch);
  for (int i = -n; i <= n; ++i)
    for (int k = -n; k <= n; ++k)
      for (int j = 0; j <= m; ++j) {
        const double x = i * kPitch, y = kR + j * kPitch, z = k * kPitch;
        if (keep(x, y, z)) p.add(x, y, z);
      }
  return p;
}

// A cone of slope angle `a` and height h on a floor, its axis the y axis.
Pack cone(double a, double h) {
  const double base = h / std::tan(a);
  return lattice(base + 2 * kPitch, h,
                 [&](double x, double y, double z) { return y <= h - std::hypot(x, z) * std::tan(a); });
}

// The staircase bound above, for a band of errors `band` wide (one pitch on the lattice).
void check_slope(const gf::ReposeFlank& f, double true_angle, double band = kPitch) {
  REQUIRE(f.columns >= 5);
  const double span = f.s_to - f.s_from;
  INFO("measured " << f.angle / kDeg << " deg over " << f.columns << " columns spanning " << span * 1e3 << " mm, true "
                   << true_angle / kDeg << " deg, slope bound " << 0.75 * band / span);
  CHECK(std::abs(std::tan(f.angle) - std::tan(true_angle)) <= 0.75 * band / span + 1e-12);
}

gf::ReposeSettings settings(double column = 2e-3) {
  gf::ReposeSettings s;
  s.column = column;
  return s;
}

const gf::V3<double> kUp{0, 1, 0};

}  // namespace

TEST_CASE("repose: a cone's slope is found at 20, 30 and 40 degrees", "[repose]") {
  for (const double deg : {20.0, 30.0, 40.0}) {
    const Pack p = cone(deg * kDeg, 0.02);
    const gf::Repose r = gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings());
    check_slope(r.first, deg * kDeg);
    CHECK(r.first.slope < 0.0);  // the surface falls away from the axis
    CHECK(std::isnan(r.second.angle));
    // The top column's surface: the cone's tip within a pitch (the lattice's highest grain top).
    CHECK(r.extreme_height == Approx(0.02).margin(2 * kPitch));
  }
}

TEST_CASE("repose: a ridge's two flanks, and the crater a hopper leaves, planar", "[repose]") {
  // A ridge along z: height h - |x| tan a; two flanks at +a and -a slopes.
  const double a = 35.0 * kDeg, h = 0.02;
  const Pack ridge = lattice(h / std::tan(a) + 2 * kPitch, h,
                             [&](double x, double y, double) { return y <= h - std::abs(x) * std::tan(a); });
  const gf::Repose r = gf::repose_planar(ridge.view(), {1, 0, 0}, kUp, settings());
  check_slope(r.first, a);
  check_slope(r.second, a);
  CHECK(r.first.slope > 0.0);
  CHECK(r.second.slope < 0.0);
  CHECK(r.extreme_s == Approx(0.0).margin(2e-3));
  // A crater: a box of grains with a V cut out about x = 0 at 28 degrees, down to 2 mm above the floor.
  const double b = 28.0 * kDeg, top = 0.025;
  const Pack crater = lattice(0.04, top, [&](double x, double y, double) {
    return y <= std::min(top, 0.002 + std::abs(x) * std::tan(b));
  });
  const gf::Repose c = gf::repose_planar(crater.view(), {1, 0, 0}, kUp, settings(), true);
  check_slope(c.first, b);
  check_slope(c.second, b);
  CHECK(c.first.slope < 0.0);
  CHECK(c.second.slope > 0.0);
  // Read as a heap, the same profile has its crest on the plateau and no fitted flank there.
  CHECK(c.extreme_height < 0.005);
}

TEST_CASE("repose: grains in flight and a tilted frame leave the angle as it was", "[repose]") {
  Pack p = cone(30.0 * kDeg, 0.02);
  const gf::Repose before = gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings());
  // Two grains high above one column (rank 3: the column's surface is its third highest top).
  p.add(0.012, 0.05, 0.0);
  p.add(0.0121, 0.06, 0.0);
  const gf::Repose flying = gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings());
  CHECK(flying.first.angle == before.first.angle);
  // The whole heap turned so that "up" is z and shifted: the same numbers.
  Pack turned;
  for (std::size_t i = 0; i < p.x.size(); ++i) turned.add(p.x[i] + 1.0, p.z[i] - 2.0, p.y[i] + 0.5);
  const gf::Repose t = gf::repose_radial(turned.view(), {1.0, -2.0, 0.5}, {0, 0, 3.0}, settings());
  CHECK(t.first.angle == Approx(flying.first.angle).margin(1e-9));
}

TEST_CASE("repose: a jittered cone stays within the widened bound", "[repose]") {
  // Each grain moved at random by up to 0.2 mm in each direction (a loose pack): a column's top
  // moves by up to 0.2 mm either way, so its error band widens from p to p + 0.4 mm.
  Pack p = cone(32.0 * kDeg, 0.02);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> d(-0.2e-3, 0.2e-3);
  for (std::size_t i = 0; i < p.x.size(); ++i) {
    p.x[i] += d(rng);
    p.y[i] += d(rng);
    p.z[i] += d(rng);
  }
  const gf::Repose r = gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings());
  check_slope(r.first, 32.0 * kDeg, kPitch + 0.4e-3);
}

TEST_CASE("repose: too few columns give NaN, bad settings are refused", "[repose]") {
  const Pack flat = lattice(0.01, 0.0, [](double, double, double) { return true; });
  const gf::Repose f = gf::repose_planar(flat.view(), {1, 0, 0}, kUp, settings());
  CHECK(std::isnan(f.first.angle));  // a flat layer: no height range, no flank
  CHECK(std::isnan(gf::repose_radial(gf::ReposeGrains{}, {0, 0, 0}, kUp, settings()).first.angle));
  const Pack p = cone(30.0 * kDeg, 0.01);
  CHECK_THROWS_AS(gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings(0.0)), std::invalid_argument);
  CHECK_THROWS_AS(gf::repose_radial(p.view(), {0, 0, 0}, {0, 0, 0}, settings()), std::invalid_argument);
  CHECK_THROWS_AS(gf::repose_planar(p.view(), {0, 2, 0}, kUp, settings()), std::invalid_argument);
  gf::ReposeSettings bad = settings();
  bad.lower = 0.9;
  bad.upper = 0.5;
  CHECK_THROWS_AS(gf::repose_radial(p.view(), {0, 0, 0}, kUp, bad), std::invalid_argument);
  CHECK_THROWS_AS(gf::repose_radial(p.view(), {0, 0, 0}, kUp, settings(1e-12)), std::invalid_argument);
}
