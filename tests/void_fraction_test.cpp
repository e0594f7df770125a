// The grains as the liquid sees them (systems/coupling/void_fraction.hpp): each grain's volume is
// shared onto the nodes without loss, the reaction conserves momentum to rounding, uniform fields are
// read back exactly at the grains, a uniform suspension gives its solid fraction at the nodes, and a
// grain out of the liquid's reach is reported.
#include "systems/coupling/void_fraction.hpp"
#include "systems/mps/mps_coupled_liquid.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

constexpr double kL0 = 7.5e-3;  // m, the seed's node spacing

struct Points {
  std::vector<double> x, y, z;
  gf::PointSet view() const { return {x, y, z}; }
  void add(double a, double b, double c) {
    x.push_back(a);
    y.push_back(b);
    z.push_back(c);
  }
};

// A cubic lattice of nodes, n per side, spacing `a` (default l0), from the origin.
Points lattice(int n, double a = kL0) {
  Points p;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) p.add(i * a, j * a, k * a);
  return p;
}

// `count` grain centres at random inside [lo, hi]^3 (overlaps do not matter to the shares).
Points random_grains(std::size_t count, double lo, double hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(lo, hi);
  Points p;
  for (std::size_t k = 0; k < count; ++k) {
    const double a = u(rng), b = u(rng), c = u(rng);
    p.add(a, b, c);
  }
  return p;
}

}  // namespace

TEST_CASE("void fraction: each grain's volume is shared without loss", "[coupling]") {
  const Points nodes = lattice(12);
  const Points grains = random_grains(300, 2 * kL0, 9 * kL0, 1);
  const double h = 2.5 * kL0, d = 20e-3, vp = std::numbers::pi / 6.0 * d * d * d;
  const gf::GrainShares s = gf::compute_shares(grains.view(), nodes.view(), h);
  for (std::size_t p = 0; p < grains.x.size(); ++p) {
    double sum = 0.0;
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) sum += s.share[e];
    REQUIRE(sum == Approx(1.0).epsilon(1e-14));
  }
  const std::vector<double> volumes(grains.x.size(), vp);
  const std::vector<double> solid = gf::solid_volume(s, volumes, nodes.x.size());
  double total = 0.0;
  for (const double v : solid) total += v;
  CHECK(total == Approx(vp * static_cast<double>(grains.x.size())).epsilon(1e-13));
}

TEST_CASE("void fraction: the reaction conserves momentum, uniform fields read back exactly", "[coupling]") {
  const Points nodes = lattice(10);
  const Points grains = random_grains(50, 2 * kL0, 7 * kL0, 2);
  const double h = 2.0 * kL0, vi = kL0 * kL0 * kL0;
  const gf::GrainShares s = gf::compute_shares(grains.view(), nodes.view(), h);
  std::vector<gf::V3<double>> force(grains.x.size());
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  gf::V3<double> sum_grains{0, 0, 0};
  for (auto& f : force) {
    f = {u(rng), u(rng), u(rng)};
    sum_grains = sum_grains + f;
  }
  std::vector<gf::V3<double>> density(nodes.x.size());
  gf::spread_reaction(s, force, vi, density);
  gf::V3<double> sum_nodes{0, 0, 0};
  for (const auto& f : density) sum_nodes = sum_nodes + vi * f;
  CHECK(sum_nodes.x == Approx(-sum_grains.x).margin(1e-13));
  CHECK(sum_nodes.y == Approx(-sum_grains.y).margin(1e-13));
  CHECK(sum_nodes.z == Approx(-sum_grains.z).margin(1e-13));
  // A uniform field at the nodes is that value at every grain (the shares sum to one).
  const std::vector<double> field(nodes.x.size(), 0.37);
  for (const double v : gf::at_grains(s, field)) CHECK(v == Approx(0.37).epsilon(1e-14));
}

TEST_CASE("void fraction: a uniform suspension shows its solid fraction at the inner nodes", "[coupling]") {
  // Grains of 2 mm on a cubic lattice of 2.5 mm (shifted off the nodes' lattice by a third of it):
  // a uniform solid fraction phi = V_p / (2.5 mm)^3 = 0.268. A node farther than h from the cube's
  // faces gets sum_p w_ip V_p, where each share is W over the lattice sum of W around the grain:
  // both sums sample a smooth kernel at spacings a third (grains) and an eighth (nodes, l0 / h) of
  // its radius, so S_i / V_i equals phi up to that sampling (under 0.1 % here), bounded by 0.2 %.
  const Points nodes = lattice(9);  // 0 .. 60 mm
  Points grains;
  const double a = 2.5e-3;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) grains.add((i + 1.0 / 3.0) * a, (j + 1.0 / 3.0) * a, (k + 1.0 / 3.0) * a);
  const double d = 2e-3, vp = std::numbers::pi / 6.0 * d * d * d, h = 2.5 * kL0, vi = kL0 * kL0 * kL0;
  const gf::GrainShares s = gf::compute_shares(grains.view(), nodes.view(), h);
  const std::vector<double> solid = gf::solid_volume(s, std::vector<double>(grains.x.size(), vp), nodes.x.size());
  const std::vector<double> eps = gf::liquid_fraction(solid, vi, 0.2);
  const double phi = vp / (a * a * a);
  int inner = 0;
  for (std::size_t i = 0; i < nodes.x.size(); ++i) {
    const double m[3] = {nodes.x[i], nodes.y[i], nodes.z[i]};
    bool deep = true;
    for (const double c : m) deep = deep && c > h && c < 0.06 - h;
    if (!deep) continue;
    ++inner;
    INFO("node " << i << ": solid fraction " << 1.0 - eps[i] << " of " << phi);
    CHECK(1.0 - eps[i] == Approx(phi).epsilon(0.002));
  }
  CHECK(inner == 27);
}

TEST_CASE("void fraction: the nodes of a thinned (averaged) liquid hold the grains' fraction in their own volume", "[coupling]") {
  // A locally averaged liquid's nodes sit at n = eps n0 among grains of solid fraction phi = 1 - eps.
  // The suspension of the test above (phi = 0.268), with nodes on a lattice thinned to eps: spacing
  // l0 eps^(-1/3), number density eps n0 (given, as the liquid would have computed it). Each node's
  // mixture volume is then l0^3 / eps, its spacing cubed, so S_i / V_i is phi as on the full lattice
  // (the same sampling bound, 0.2 %); with the fixed l0^3 it reads phi / eps, 37 % high.
  const double a = 2.5e-3, d = 2e-3, vp = std::numbers::pi / 6.0 * d * d * d, phi = vp / (a * a * a);
  const double eps_true = 1.0 - phi, spacing = kL0 / std::cbrt(eps_true), h = 2.5 * kL0, n0 = 25.0;
  const Points nodes = lattice(8, spacing);  // 0 .. 58 mm
  Points grains;
  for (int k = 0; k < 24; ++k)
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 24; ++i) grains.add((i + 1.0 / 3.0) * a, (j + 1.0 / 3.0) * a, (k + 1.0 / 3.0) * a);
  const gf::GrainShares s = gf::compute_shares(grains.view(), nodes.view(), h);
  const std::vector<double> solid = gf::solid_volume(s, std::vector<double>(grains.x.size(), vp), nodes.x.size());
  const std::vector<double> n(nodes.x.size(), eps_true * n0);
  const std::vector<double> volume = gf::mixture_volumes(n, n0, kL0 * kL0 * kL0);
  const std::vector<double> eps = gf::liquid_fraction(solid, volume, 0.2);
  const std::vector<double> eps_fixed = gf::liquid_fraction(solid, kL0 * kL0 * kL0, 0.2);
  const double side = 7 * spacing;
  int inner = 0;
  for (std::size_t i = 0; i < nodes.x.size(); ++i) {
    bool deep = true;
    for (const double c : {nodes.x[i], nodes.y[i], nodes.z[i]}) deep = deep && c > h && c < side - h;
    if (!deep) continue;
    ++inner;
    CHECK(volume[i] == Approx(spacing * spacing * spacing).epsilon(1e-12));
    CHECK(1.0 - eps[i] == Approx(phi).epsilon(0.002));
    CHECK(1.0 - eps_fixed[i] == Approx(phi / eps_true).epsilon(0.002));
  }
  CHECK(inner == 8);
  // A node whose kernel is cut (a free surface) counts as n0 / 2 at least; one not computed yet as n0.
  const std::vector<double> edge = gf::mixture_volumes(std::vector<double>{0.1 * n0, 0.0, n0}, n0, 1.0);
  CHECK(edge[0] == 2.0);
  CHECK(edge[1] == 1.0);
  CHECK(edge[2] == 1.0);
}

TEST_CASE("void fraction: a grain beyond every node's reach is reported, the floor holds", "[coupling]") {
  const Points nodes = lattice(4);
  Points far;
  far.add(1.0, 1.0, 1.0);
  CHECK_THROWS_AS(gf::compute_shares(far.view(), nodes.view(), 2 * kL0), std::runtime_error);
  CHECK_THROWS_AS(gf::compute_shares(far.view(), nodes.view(), 0.0), std::invalid_argument);
  const std::vector<double> solid{0.0, 0.5, 2.0};
  const std::vector<double> eps = gf::liquid_fraction(solid, 1.0, 0.3);
  CHECK(eps[0] == 1.0);
  CHECK(eps[1] == 0.5);
  CHECK(eps[2] == 0.3);
}
