// The packing fraction of composite grains (systems/analysis/packing.hpp) on arrangements whose solid
// volume is known: cubes on a lattice whose faces fall on voxel faces (exact), turned cubes and a
// ball within the bound that the voxels the surface cuts put on the count, fixed and removed bodies
// not counted, bad boxes refused, and a bed's interior (away from its walls, floor and free surface)
// on a lattice of cubes, whose share is exact.
#include "systems/analysis/packing.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace {

// Cubes of side a (sharp, r = 0) centred at `centres`, turned by `angle` about z.
void add_cube(gf::Bodies& bodies, gf::Members& members, std::array<double, 3> at, double a, double angle = 0.0,
              gf::Motion motion = gf::Motion::moving) {
  gf::BodyRow row;
  row.x = at;
  row.q = {std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2)};
  row.mass = 1.0;
  row.inertia = {1.0, 1.0, 1.0};
  row.motion = motion;
  const auto b = static_cast<std::uint32_t>(bodies.push(row));
  gf::MemberRow m;
  m.body = b;
  for (const double x : {-a / 2, a / 2})
    for (const double y : {-a / 2, a / 2})
      for (const double z : {-a / 2, a / 2}) m.vertices.push_back({x, y, z});
  members.push(m);
}

}  // namespace

TEST_CASE("packing: cubes on a lattice give their volume share exactly", "[packing]") {
  // Cubes of 4 mm every 8 mm: 1/8 of the space. Voxels of 1 mm from the lattice cell's corner put
  // every cube face on voxel faces, so no voxel centre lies on a surface: the count is exact.
  gf::Bodies bodies;
  gf::Members members;
  const double a = 4e-3, s = 8e-3;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) add_cube(bodies, members, {(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s}, a);
  gf::place_members(bodies, members);
  const gf::PackingFraction f = gf::packing_fraction(bodies, members, {0, 0, 0}, {3 * s, 3 * s, 3 * s}, 1e-3);
  CHECK(f.voxels == 24u * 24u * 24u);
  CHECK(f.fraction == 0.125);
}

TEST_CASE("packing: turned cubes and a ball, within the bound of the cut voxels", "[packing]") {
  // A voxel can be counted wrongly only when the surface passes within (sqrt 3 / 2) h of its centre:
  // at most area x sqrt(3) h / h^3 voxels, a relative error of at most sqrt(3) h area / volume.
  gf::Bodies bodies;
  gf::Members members;
  const double a = 4e-3, s = 8e-3;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)  // off the voxels' symmetry: a square centred on a voxel corner counts evenly
      add_cube(bodies, members, {(i + 0.5) * s + 0.37e-3 * j, (j + 0.5) * s + 0.21e-3 * i, 0.5 * s + 0.13e-3},
               a, 0.3 + 0.2 * i + 0.1 * j);
  gf::place_members(bodies, members);
  const double box = 2 * s * 2 * s * s, want = 4 * a * a * a / box;
  double last = 1.0;
  for (const double h : {0.4e-3, 0.2e-3, 0.1e-3}) {
    const gf::PackingFraction f = gf::packing_fraction(bodies, members, {0, 0, 0}, {2 * s, 2 * s, s}, h);
    const double error = std::abs(f.fraction - want) / want, bound = std::sqrt(3.0) * h * 6.0 / a;
    INFO("h " << h << ": " << f.fraction << " against " << want << ", relative error " << error << ", bound " << bound);
    CHECK(error <= bound);
    last = error;
  }
  CHECK(last < 0.005);  // measured: 2.5e-3 at h = a / 10 and a / 20, none left at a / 40
  // A ball: a point core of radius r = 3 mm in a 10 mm box.
  gf::Bodies ball_bodies;
  gf::Members ball_members;
  gf::BodyRow row;
  row.x = {5e-3, 5e-3, 5e-3};
  row.mass = 1.0;
  row.inertia = {1.0, 1.0, 1.0};
  ball_bodies.push(row);
  ball_members.push({0, {{0.0, 0.0, 0.0}}, 3e-3});
  gf::place_members(ball_bodies, ball_members);
  const double r = 3e-3, h = 0.1e-3;
  const gf::PackingFraction f = gf::packing_fraction(ball_bodies, ball_members, {0, 0, 0}, {1e-2, 1e-2, 1e-2}, h);
  const double ball = 4.0 / 3.0 * std::numbers::pi * r * r * r / 1e-6;
  CHECK(std::abs(f.fraction - ball) / ball <= std::sqrt(3.0) * h * 3.0 / r);
}

TEST_CASE("packing: fixed and removed bodies are not grains, and bad boxes are refused", "[packing]") {
  gf::Bodies bodies;
  gf::Members members;
  add_cube(bodies, members, {4e-3, 4e-3, 4e-3}, 4e-3, 0.0, gf::Motion::fixed);
  add_cube(bodies, members, {12e-3, 4e-3, 4e-3}, 4e-3);
  gf::remove_body(bodies, 1);
  gf::place_members(bodies, members);
  CHECK(gf::packing_fraction(bodies, members, {0, 0, 0}, {16e-3, 8e-3, 8e-3}, 1e-3).solid == 0);
  CHECK_THROWS_AS(gf::packing_fraction(bodies, members, {0, 0, 0}, {0, 1, 1}, 1e-3), std::invalid_argument);
  CHECK_THROWS_AS(gf::packing_fraction(bodies, members, {0, 0, 0}, {1, 1, 1}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::packing_fraction(bodies, members, {0, 0, 0}, {1, 1, 1}, 1e-6), std::invalid_argument);
}

TEST_CASE("packing: a bed's interior, away from its walls, floor and surface, on a lattice of cubes", "[packing]") {
  // Cubes of 4 mm every 8 mm, 6 x 6 x 6 from 0 to 48 mm: the bed's solid extent is [2, 46] mm on every
  // axis. A margin of 6 mm leaves [8, 40] mm, four whole lattice cells, where the cubes fill exactly
  // 1/8; the free surface lies on the top layer's top faces, 44 mm above the floor; the whole bed
  // (from the floor to the surface, across the full extent) holds 24 mm of solid in every 44 mm, so
  // (6/11)^3. Voxels of 1 mm on a grid from the origin put every face on voxel faces, so no voxel
  // centre lies on a surface: every count is exact, and so is the comparison.
  const double a = 4e-3, s = 8e-3, margin = 6e-3, h = 1e-3;
  struct Case {
    int up, sign;
  };
  for (const Case c : {Case{1, 1}, Case{1, -1}, Case{2, 1}, Case{0, -1}}) {
    gf::Bodies bodies;
    gf::Members members;
    for (int i = 0; i < 6; ++i)
      for (int j = 0; j < 6; ++j)
        for (int k = 0; k < 6; ++k) add_cube(bodies, members, {(i + 0.5) * s, (j + 0.5) * s, (k + 0.5) * s}, a);
    gf::place_members(bodies, members);
    const gf::BedPacking p = gf::bed_packing(bodies, members, c.up, c.sign, margin, h);
    INFO("up axis " << c.up << ", sign " << c.sign << ": " << p.reason);
    REQUIRE(p.valid);
    CHECK(p.interior.fraction == 0.125);
    CHECK(p.whole.fraction == 216.0 / 1331.0);
    CHECK(p.floor == Approx(c.sign > 0 ? 2e-3 : 46e-3).margin(1e-12));
    CHECK(p.surface == Approx(c.sign > 0 ? 46e-3 : 2e-3).margin(1e-12));
    for (int d = 0; d < 3; ++d) {
      CHECK(p.lo[d] == Approx(8e-3).margin(1e-12));
      CHECK(p.hi[d] == Approx(40e-3).margin(1e-12));
      CHECK(p.bed_lo[d] == Approx(2e-3).margin(1e-12));
      CHECK(p.bed_hi[d] == Approx(46e-3).margin(1e-12));
    }
    // The profile: 44 layers from the floor; a layer through cubes is 1/4 solid in the interior's
    // columns (two 4 mm squares in every 8 mm square) and (24/44)^2 across the whole extent, one
    // between the cubes' layers empty.
    REQUIRE(p.layers.size() == 44);
    CHECK(p.layers[0].height == Approx(0.5e-3).margin(1e-12));
    CHECK(p.layers[0].interior == 0.25);
    CHECK(p.layers[0].whole == Approx(36.0 / 121.0).epsilon(1e-15));
    CHECK(p.layers[5].interior == 0.0);
  }
  // One layer of cubes is shallower than two margins: no interior.
  gf::Bodies bodies;
  gf::Members members;
  for (int i = 0; i < 6; ++i)
    for (int k = 0; k < 6; ++k) add_cube(bodies, members, {(i + 0.5) * s, 0.5 * s, (k + 0.5) * s}, a);
  gf::place_members(bodies, members);
  const gf::BedPacking thin = gf::bed_packing(bodies, members, 1, 1, margin, h);
  CHECK_FALSE(thin.valid);
  CHECK(thin.reason == "the bed is shallower than two margins");
  CHECK_FALSE(gf::bed_packing(bodies, members, 1, 1, 0.2, h).valid);  // narrower than two margins
  CHECK_THROWS_AS(gf::bed_packing(bodies, members, 3, 1, margin, h), std::invalid_argument);
  CHECK_THROWS_AS(gf::bed_packing(bodies, members, 1, 1, margin, 0.0), std::invalid_argument);
}
