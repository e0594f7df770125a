// Shares on a periodic liquid (compute_shares_periodic, systems/coupling/void_fraction.hpp): a grain near
// one end of the periodic axis shares its volume with the nodes at the other end as a grain in the
// middle does with its neighbours, so a bed that fills a periodic column has no seam; grains and nodes
// that stand past a face count as their wrapped twins.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "systems/coupling/void_fraction.hpp"

namespace {

constexpr double kL0 = 1.0e-3;  // m
constexpr int kN = 10;          // nodes per side; periodic along x over [0, kN l0)

struct Points {
  std::vector<double> x, y, z;
  gf::PointSet view() const { return {x, y, z}; }
};

Points nodes() {
  Points p;
  for (int k = 0; k < kN; ++k)
    for (int j = 0; j < kN; ++j)
      for (int i = 0; i < kN; ++i) {
        p.x.push_back((i + 0.5) * kL0);
        p.y.push_back((j + 0.5) * kL0);
        p.z.push_back((k + 0.5) * kL0);
      }
  return p;
}

// The solid volume (of a grain of volume 1) at each node, with the nodes periodic along x.
std::vector<double> solid_of_grain_at(double x, const Points& n) {
  const Points g{{x}, {4.3 * kL0}, {5.2 * kL0}};
  const gf::GrainShares s = gf::compute_shares_periodic(g.view(), n.view(), 2.5 * kL0, 0, 0.0, kN * kL0);
  return gf::solid_volume(s, std::vector<double>{1.0}, n.x.size());
}

}  // namespace

TEST_CASE("periodic shares: a grain at the seam shares as one in the middle, shifted", "[coupling]") {
  const Points n = nodes();
  const std::vector<double> seam = solid_of_grain_at(0.2 * kL0, n), middle = solid_of_grain_at(5.2 * kL0, n);
  double total = 0.0, worst = 0.0;
  for (std::size_t r = 0; r < seam.size(); ++r) {
    const std::size_t i = r % kN, shifted = r - i + (i + 5) % kN;  // the node 5 l0 further along x
    total += seam[r];
    worst = std::max(worst, std::abs(seam[r] - middle[shifted]));
  }
  CHECK(total == Approx(1.0).epsilon(1e-14));
  CHECK(worst < 1e-12);
  // Without the images the seam grain keeps its whole volume on one side: more on the nodes it reaches.
  const Points g{{0.2 * kL0}, {4.3 * kL0}, {5.2 * kL0}};
  const std::vector<double> open =
      gf::solid_volume(gf::compute_shares(g.view(), n.view(), 2.5 * kL0), std::vector<double>{1.0}, n.x.size());
  const std::size_t first = 4 * kN + 5 * kN * kN;  // node (0.5, 4.5, 5.5) l0
  CHECK(open[first] > 1.2 * seam[first]);
}

TEST_CASE("periodic shares: grains and nodes a little past a face share as their wrapped twins", "[coupling]") {
  // Between list rebuilds both may stand up to half a skin past a face: a grain at -0.3 l0 is the grain
  // at 9.7 l0, and a node at 10.2 l0 the node at 0.2 l0.
  Points n = nodes();
  const std::vector<double> inside = solid_of_grain_at(9.7 * kL0, n), outside = solid_of_grain_at(-0.3 * kL0, n);
  double worst = 0.0;
  for (std::size_t r = 0; r < inside.size(); ++r) worst = std::max(worst, std::abs(inside[r] - outside[r]));
  CHECK(worst < 1e-12);
  Points moved = n;
  for (double& x : moved.x)
    if (x < kL0) x += kN * kL0;  // the first layer stands past the far face
  const std::vector<double> with_moved = solid_of_grain_at(9.7 * kL0, moved);
  worst = 0.0;
  for (std::size_t r = 0; r < inside.size(); ++r) worst = std::max(worst, std::abs(inside[r] - with_moved[r]));
  CHECK(worst < 1e-12);
}

TEST_CASE("periodic shares: a period that is not one is refused", "[coupling]") {
  const Points n = nodes();
  const Points g{{0.2 * kL0}, {4.3 * kL0}, {5.2 * kL0}};
  CHECK_THROWS_AS(gf::compute_shares_periodic(g.view(), n.view(), 2.5 * kL0, 0, 1.0, 1.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::compute_shares_periodic(g.view(), n.view(), 2.5 * kL0, 3, 0.0, 1.0), std::invalid_argument);
}
