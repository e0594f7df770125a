// Random sequential addition: geometry of the region, non-overlap, exact counts, determinism,
// and the error a user gets when the request cannot be packed.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <string>

#include "systems/fill/random_fill.hpp"
#include "systems/fill/region.hpp"

using gf::FillError;
using gf::FillSpecies;
using gf::PlacedGrain;
using gf::Region;

namespace {

double sphere_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// Every pair, no grid: the reference the grid-based check in place_random must agree with.
// Touching is allowed; the relative 1e-12 absorbs rounding in the two distance computations.
std::size_t count_overlaps(const std::vector<PlacedGrain>& a, const std::vector<PlacedGrain>& b,
                           bool same) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = same ? i + 1 : 0; j < b.size(); ++j) {
      const double dx = a[i].x[0] - b[j].x[0];
      const double dy = a[i].x[1] - b[j].x[1];
      const double dz = a[i].x[2] - b[j].x[2];
      const double sum = a[i].radius + b[j].radius;
      if (std::sqrt(dx * dx + dy * dy + dz * dz) < sum * (1.0 - 1e-12)) ++n;
    }
  }
  return n;
}

std::map<std::int32_t, std::size_t> count_types(const std::vector<PlacedGrain>& g) {
  std::map<std::int32_t, std::size_t> n;
  for (const PlacedGrain& p : g) ++n[p.type];
  return n;
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

TEST_CASE("region volumes match closed forms and a Monte Carlo estimate", "[fill]") {
  const double R = 0.01;
  const double L = 0.02;
  const double full = std::numbers::pi * R * R * L;

  SECTION("box and whole cylinder") {
    CHECK(Region::box({0, 0, 0}, {0.1, 0.2, 0.3}).volume() == Approx(0.006).epsilon(1e-14));
    CHECK(Region::cylinder({1, 2, 3}, {1, 1, 0}, R, L).volume() == Approx(full).epsilon(1e-14));
  }
  SECTION("level axis cut through the centre keeps half") {
    const Region r = Region::cylinder({0, 0, 0}, {0, 0, 1}, R, L, 0.0, {0, 1, 0});
    CHECK(r.volume() == Approx(0.5 * full).epsilon(1e-12));
    // Circular segment below height R/2: R^2 acos(-1/2) + (R/2) sqrt(3/4) R, times L.
    const Region s = Region::cylinder({0, 0, 0}, {0, 0, 1}, R, L, 0.5 * R, {0, 1, 0});
    const double seg = R * R * (2.0 * std::numbers::pi / 3.0) + 0.5 * R * std::sqrt(0.75) * R;
    CHECK(s.volume() == Approx(seg * L).epsilon(1e-12));
  }
  SECTION("up along the axis shortens the cylinder") {
    const Region r = Region::cylinder({0, 0, 0}, {0, 0, 1}, R, L, 0.25 * L, {0, 0, 1});
    CHECK(r.volume() == Approx(0.75 * full).epsilon(1e-12));
    const Region d = Region::cylinder({0, 0, 0}, {0, 0, 1}, R, L, 0.25 * L, {0, 0, -1});
    CHECK(d.volume() == Approx(0.75 * full).epsilon(1e-12));
  }
  SECTION("tilted cut, plane crossing the end faces") {
    // Closed form against counting random points: with N points the hit fraction f has standard
    // error sqrt(f(1-f)/N) ~ 1.1e-3 of the box here; 4 sigma cannot fail by chance but does catch
    // a sign or factor slip in the formula (those move the volume by 10 % or more).
    for (const double h : {-0.004, 0.0, 0.003}) {
      const Region r = Region::cylinder({0.1, -0.2, 0.3}, {0.3, 0.2, 1.0}, R, L, h, {0, 1, 0.5});
      const auto lo = r.bbox_lo();
      const auto hi = r.bbox_hi();
      std::mt19937_64 rng(7);
      const int n = 200000;
      int inside = 0;
      for (int k = 0; k < n; ++k) {
        std::array<double, 3> p;
        for (int i = 0; i < 3; ++i) {
          p[i] = lo[i] + (hi[i] - lo[i]) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
        }
        inside += r.contains_sphere(p, 0.0) ? 1 : 0;
      }
      const double box = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
      const double f = static_cast<double>(inside) / n;
      const double sigma = box * std::sqrt(f * (1.0 - f) / n);
      INFO("max_height " << h << ": closed form " << r.volume() << ", Monte Carlo " << f * box);
      CHECK(std::abs(r.volume() - f * box) < 4.0 * sigma);
      CHECK(r.volume() < full);
    }
  }
  SECTION("bad regions are reported, not used") {
    CHECK_FALSE(Region::box({0, 0, 0}, {1, 1, 1}).problem().size() > 0);
    CHECK(Region::box({0, 0, 0}, {1, -1, 1}).problem().find("hi <= lo") != std::string::npos);
    CHECK(Region::cylinder({0, 0, 0}, {0, 0, 1}, 0.0, 1.0).problem().find("radius") !=
          std::string::npos);
    CHECK(Region::cylinder({0, 0, 0}, {0, 0, 1}, 1.0, 1.0, -2.0).problem().find("max_height") !=
          std::string::npos);
    REQUIRE_THROWS_AS(gf::place_random(Region::box({0, 0, 0}, {1, -1, 1}), {{1, 0.1, 1}}, 1),
                      FillError);
  }
}

TEST_CASE("box fill: inside, non-overlapping, exact counts, largest first", "[fill]") {
  const Region box = Region::box({-0.01, 0.0, 0.005}, {0.01, 0.02, 0.025});
  // Two small species of equal radius, to see them interleaved rather than one after the other.
  const std::vector<FillSpecies> species{{1, 0.5e-3, 1300}, {3, 0.5e-3, 1300}, {2, 1.0e-3, 250}};
  const auto g = gf::place_random(box, species, 42);

  REQUIRE(g.size() == 2850);
  const auto n = count_types(g);
  CHECK(n.at(1) == 1300);
  CHECK(n.at(2) == 250);
  CHECK(n.at(3) == 1300);
  for (const PlacedGrain& p : g) {
    REQUIRE(box.contains_sphere(p.x, p.radius));
    for (int i = 0; i < 3; ++i) {
      REQUIRE(p.x[i] - p.radius >= box.lo[i]);
      REQUIRE(p.x[i] + p.radius <= box.hi[i]);
    }
  }
  CHECK(count_overlaps(g, g, true) == 0);

  for (std::size_t k = 0; k < 250; ++k) CHECK(g[k].type == 2);
  // A type-blind shuffle puts ~650 of type 3 among the first 1300 small grains (sd ~18); ordering
  // by species would put 0 or 1300 there.
  std::size_t threes = 0;
  for (std::size_t k = 250; k < 250 + 1300; ++k) threes += g[k].type == 3 ? 1 : 0;
  CHECK(threes > 550);
  CHECK(threes < 750);
}

TEST_CASE("height-limited tilted cylinder fill, then a fill around existing grains", "[fill]") {
  const std::array<double, 3> c{0.01, -0.02, 0.0};
  const std::array<double, 3> up{0.0, 0.6, 0.8};
  const Region lower = Region::cylinder(c, {1.0, 1.0, 0.2}, 0.012, 0.02, 0.002, up);
  const auto a = lower.axis;
  const std::size_t n_small = gf::count_for_volume_fraction(lower, 0.18, 0.4e-3);
  const std::size_t n_big = gf::count_for_volume_fraction(lower, 0.1, 0.8e-3);
  const auto g = gf::place_random(lower, {{1, 0.4e-3, n_small}, {2, 0.8e-3, n_big}}, 5);
  REQUIRE(g.size() == n_small + n_big);
  REQUIRE(g.size() > 1500);
  const auto n = count_types(g);
  CHECK(n.at(1) == n_small);
  CHECK(n.at(2) == n_big);

  // Inside, checked from the definition rather than through contains_sphere.
  for (const PlacedGrain& p : g) {
    const std::array<double, 3> d{p.x[0] - c[0], p.x[1] - c[1], p.x[2] - c[2]};
    const double s = dot(d, a);
    const std::array<double, 3> q{d[0] - s * a[0], d[1] - s * a[1], d[2] - s * a[2]};
    REQUIRE(std::abs(s) + p.radius <= 0.01 * (1 + 1e-12));
    REQUIRE(std::sqrt(dot(q, q)) + p.radius <= 0.012 * (1 + 1e-12));
    REQUIRE(dot(d, up) + p.radius <= 0.002 + 1e-15);
  }
  CHECK(count_overlaps(g, g, true) == 0);

  // The rest of the cylinder, filled around the grains already there.
  const Region whole = Region::cylinder(c, {1.0, 1.0, 0.2}, 0.012, 0.02);
  const auto more = gf::place_random(whole, {{4, 0.6e-3, 800}}, 6, g);
  REQUIRE(more.size() == 800);
  for (const PlacedGrain& p : more) REQUIRE(whole.contains_sphere(p.x, p.radius));
  CHECK(count_overlaps(more, more, true) == 0);
  CHECK(count_overlaps(more, g, false) == 0);
  // Some of the new grains went below the cut, between the old ones: existing grains are obstacles,
  // not a floor.
  std::size_t below = 0;
  for (const PlacedGrain& p : more) {
    const std::array<double, 3> d{p.x[0] - c[0], p.x[1] - c[1], p.x[2] - c[2]};
    below += dot(d, up) < 0.0 ? 1 : 0;
  }
  CHECK(below > 0);
}

TEST_CASE("the same seed gives the same fill, another seed another", "[fill]") {
  const Region r = Region::cylinder({0, 0, 0}, {0, 0, 1}, 0.01, 0.004, 0.0, {0, 1, 0});
  const std::vector<FillSpecies> sp{{1, 0.3e-3, 900}, {2, 0.6e-3, 80}};
  const auto a = gf::place_random(r, sp, 123);
  const auto b = gf::place_random(r, sp, 123);
  const auto c = gf::place_random(r, sp, 124);
  REQUIRE(a.size() == b.size());
  REQUIRE(a.size() == c.size());
  bool identical = true;
  bool differ = false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    identical = identical && a[k].x == b[k].x && a[k].type == b[k].type;
    differ = differ || a[k].x != c[k].x;
  }
  CHECK(identical);
  CHECK(differ);
}

TEST_CASE("the seed drum fill (47,108 grains, solid fraction 0.34) succeeds", "[fill]") {
  // The pour that drum_settled_47108.csv was settled from; it must not need tuning of attempts.
  const Region drum = Region::cylinder({0, 0, 0}, {0, 0, 1}, 0.075, 0.008);
  const auto g = gf::place_random(drum, {{1, 0.5e-3, 45426}, {2, 1.5e-3, 1682}}, 1);
  REQUIRE(g.size() == 47108);
  double v = 0.0;
  for (const PlacedGrain& p : g) v += sphere_volume(p.radius);
  CHECK(v / drum.volume() == Approx(0.3364).epsilon(1e-3));
}

TEST_CASE("an impossible fill says what it reached and what to change", "[fill]") {
  // Random sequential addition of equal spheres jams at 0.38; 0.7 cannot be reached.
  const Region box = Region::box({0, 0, 0}, {0.01, 0.01, 0.01});
  const std::size_t n = gf::count_for_volume_fraction(box, 0.7, 0.5e-3);
  try {
    gf::place_random(box, {{7, 0.5e-3, n}}, 3);
    FAIL("expected a FillError");
  } catch (const FillError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK(m.find("placed") != std::string::npos);
    CHECK(m.find("of species 7") != std::string::npos);
    CHECK(m.find("requested") != std::string::npos);
    CHECK(m.find("of 0.70") != std::string::npos);
    CHECK(m.find("Fix") != std::string::npos);
    CHECK(m.find("fill in layers") != std::string::npos);
  }

  // A sphere wider than the region fails for lack of room, not of luck, and says so.
  try {
    gf::place_random(box, {{1, 0.006, 1}}, 3, {}, 50);
    FAIL("expected a FillError");
  } catch (const FillError& e) {
    CHECK(std::string(e.what()).find("no room") != std::string::npos);
  }
  CHECK_THROWS_AS(gf::place_random(box, {{1, -1.0, 1}}, 3), FillError);
}

TEST_CASE("count for a volume fraction", "[fill]") {
  const Region box = Region::box({0, 0, 0}, {0.01, 0.01, 0.01});
  // 0.3 * 1e-6 m^3 / (4/3 pi 0.5e-3^3 m^3) = 572.96
  CHECK(gf::count_for_volume_fraction(box, 0.3, 0.5e-3) == 573);
  CHECK(gf::count_for_volume_fraction(box, 0.0, 0.5e-3) == 0);
  const Region drum = Region::cylinder({0, 0, 0}, {0, 0, 1}, 0.075, 0.008);
  // The seed drum's big grains: 1682 of 3 mm are a solid fraction of 0.16822.
  CHECK(gf::count_for_volume_fraction(drum, 0.16822, 1.5e-3) == 1682);
  CHECK_THROWS_AS(gf::count_for_volume_fraction(box, -0.1, 0.5e-3), FillError);
  CHECK_THROWS_AS(gf::count_for_volume_fraction(box, 0.3, 0.0), FillError);
}

TEST_CASE("a sparse fill of a wide flat region does not build a huge grid", "[fill]") {
  // Cells of one diameter would be 2e8 here (800 MB of cell heads); the grid coarsens instead.
  const Region slab = Region::box({0, 0, 0}, {10.0, 10.0, 0.002});
  const auto g = gf::place_random(slab, {{1, 0.5e-3, 500}}, 9);
  REQUIRE(g.size() == 500);
  for (const PlacedGrain& p : g) REQUIRE(slab.contains_sphere(p.x, p.radius));
  CHECK(count_overlaps(g, g, true) == 0);
}
