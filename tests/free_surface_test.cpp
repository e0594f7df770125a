// The free surface of a drum's bed (angle, level, bulge, surface speed) on synthetic beds in seed
// 000's geometry (150 mm drum, 8 mm thick, 1 and 3 mm grains), whose surface is known by
// construction: exact column tops for the algebra, random beds for the third-highest-top rule.
#include "systems/analysis/free_surface.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "tests/test_support.hpp"

namespace {

constexpr double kR = 0.075, kLength = 0.008;

struct Bed {
  std::vector<double> x, y, z, r, vx, vy, vz;
  gf::SurfaceGrains view(bool moving = true) const {
    if (!moving) return {x, y, z, r, {}, {}, {}};
    return {x, y, z, r, vx, vy, vz};
  }
  void add(double u, double v, double rad) {
    x.push_back(u);
    y.push_back(v);
    z.push_back(0.0);
    r.push_back(rad);
    vx.push_back(0.0);
    vy.push_back(0.0);
    vz.push_back(0.0);
  }
};

gf::DrumSection section() { return gf::test::drum_section_z(kR); }

// Surface height v = f(u).
using Height = std::function<double(double)>;

Height parabola(double level, double tilt, double c) {
  return [=](double u) { return level + std::tan(tilt) * u + c * u * u; };
}

// Random grains (radius rad) at solid fraction 0.6 below the surface, inside the drum.
Bed random_bed(const Height& f, double rad, std::uint64_t seed) {
  Bed bed;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uu(-kR, kR), uz(-0.5, 0.5);
  const double vol = 4.0 / 3.0 * std::numbers::pi * rad * rad * rad;
  const auto n = static_cast<std::size_t>(0.6 * (2 * kR) * (2 * kR) * kLength / vol);
  for (std::size_t k = 0; k < n; ++k) {
    const double u = uu(rng), v = uu(rng);
    if (u * u + v * v > (kR - rad) * (kR - rad) || v + rad > f(u)) continue;
    bed.add(u, v, rad);
    bed.z.back() = uz(rng) * (kLength - 2 * rad);
  }
  return bed;
}

// Three grains per column whose tops lie exactly on the surface at the column's centre, over
// the whole drum width, with grains below them: every column's third-highest top is f(centre).
Bed exact_bed(const Height& f, double rad) {
  Bed bed;
  const double w = 4 * rad;  // the column width the method takes for these grains
  for (int c = 0; c < static_cast<int>(std::ceil(2 * kR / w)); ++c) {
    const double u = -kR + (c + 0.5) * w, top = f(u);
    if (std::hypot(u, top) > kR - 2 * rad) continue;
    for (int k = 0; k < 3; ++k) bed.add(u, top - rad, rad);
    for (int k = 1; k < 4; ++k) bed.add(u, top - rad - 2 * k * rad, rad);
  }
  return bed;
}

}  // namespace

TEST_CASE("free surface: exact column tops give the parabola's bulge and the line's angle", "[free_surface]") {
  for (const double c : {-3.0, 0.0, 3.0}) {
    INFO("u^2 coefficient " << c);
    const Bed bed = exact_bed(parabola(0.004, 0.5, c), 1.5e-3);
    const gf::FreeSurface s = gf::free_surface(bed.view(false), section());
    REQUIRE(std::isfinite(s.span));
    // The fit is exact on exact points: the bulge is -c (L/2)^2 up to round-off of the normal
    // equations (u ~ 0.1 m, so terms ~1e-4; 1e-12 m is far below).
    CHECK(s.bulge == Approx(-c * 0.25 * s.span * s.span).margin(1e-12));
    if (c == 0.0) CHECK(s.angle == Approx(0.5).margin(1e-12));
    CHECK(std::isnan(s.speed));
  }
}

TEST_CASE("free surface: random beds read convex, flat and concave surfaces", "[free_surface]") {
  // Small grains (1 mm): a column's third-highest top lies below the true surface by a random part
  // of a diameter, nearly the same in every column, so the parabola fitted over about 15 columns
  // keeps the bulge within 0.14 mm (the largest error over seeds 7 to 10); 0.5 mm is over three
  // times that. The built bulges are 7 to 8 mm.
  for (const double c : {-4.0, 0.0, 4.0}) {
    INFO("u^2 coefficient " << c);
    const Bed bed = random_bed(parabola(0.004, 0.45, c), 0.5e-3, 7);
    const gf::FreeSurface s = gf::free_surface(bed.view(false), section());
    REQUIRE(std::isfinite(s.span));
    const double built = -c * 0.25 * s.span * s.span;
    CHECK(s.bulge == Approx(built).margin(5e-4));
    if (c != 0.0) CHECK(s.bulge * built > 0);  // the sign: convex > 0, concave < 0
  }
}

TEST_CASE("free surface: the speed is that of the layer at the surface, down the slope", "[free_surface]") {
  const double tilt = 0.5, U = 0.12, rad = 0.5e-3;
  const Height f = parabola(0.004, tilt, 0.0);
  Bed bed = random_bed(f, rad, 11);
  // Grains whose tops lie within 8 mm of the surface run down it at U; deeper ones climb with the
  // wall at U. The layer read is 2 large diameters (2 mm) about the fitted line, which lies within
  // a diameter of the true one: all of it runs down.
  for (std::size_t i = 0; i < bed.x.size(); ++i) {
    const double sign = bed.y[i] + rad > f(bed.x[i]) - 8e-3 ? 1.0 : -1.0;
    bed.vx[i] = -sign * U * std::cos(tilt);
    bed.vy[i] = -sign * U * std::sin(tilt);
    bed.vz[i] = 0.01 * (i % 2 ? 1 : -1);  // along the axis: not part of the speed
  }
  const gf::FreeSurface s = gf::free_surface(bed.view(), section());
  REQUIRE(s.layer_grains > 100);
  // U cos(fitted - built angle): the fitted angle is within 0.01 rad of the tilt, so 5e-5 relative.
  CHECK(s.speed == Approx(U).epsilon(1e-4));
  CHECK(s.angle == Approx(tilt).margin(0.01));

  // Deeper grains are left out: the same bed with the whole layer reversed reads -U.
  for (std::size_t i = 0; i < bed.x.size(); ++i) bed.vx[i] = -bed.vx[i], bed.vy[i] = -bed.vy[i];
  CHECK(gf::free_surface(bed.view(), section()).speed == Approx(-U).epsilon(1e-4));
}

TEST_CASE("free surface: no bed, no surface; bad input is refused", "[free_surface]") {
  const Bed empty;
  const gf::FreeSurface s = gf::free_surface(empty.view(false), section());
  CHECK(std::isnan(s.angle));
  CHECK(std::isnan(s.bulge));
  CHECK(std::isnan(s.speed));
  Bed bed = exact_bed(parabola(0.0, 0.3, 0.0), 1.5e-3);
  bed.vx.pop_back();
  CHECK_THROWS_AS(gf::free_surface(bed.view(), section()), std::invalid_argument);
  const Bed ok = exact_bed(parabola(0.0, 0.3, 0.0), 1.5e-3);
  CHECK_THROWS_AS(gf::free_surface(ok.view(), section(), {0.0}), std::invalid_argument);
}
