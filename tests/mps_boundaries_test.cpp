// Wall and dummy layers generated from geometry (systems/mps/boundaries.hpp): kinds by distance from the fluid
// region for the tank, channel and pipe; full lattice support for near-wall fluid nodes, across a periodic
// axis too; the hydrostatic extrapolation of dummy pressures.
#include <catch2/catch.hpp>

#include <cmath>

#include "systems/mps/boundaries.hpp"
#include "systems/mps/number_density.hpp"

using namespace gf;

TEST_CASE("tank: fluid inside, one wall layer then dummies, open top; near-wall fluid sees the full lattice") {
  LiquidGeometry g;
  g.kind = LiquidGeometry::Kind::Tank;
  g.dim = 2;
  g.lo = {0, 0, 0};
  g.hi = {0.1, 0.08, 0};
  g.layers = 3;
  const double l0 = 0.01;
  FluidNodes f;
  generate_nodes(g, {FluidBlock{{0, 0, 0}, {0.1, 0.05, 0}}}, l0, f);
  CHECK(f.count(kFluid) == 10 * 5);
  for (std::size_t i = 0; i < f.size(); ++i) {
    // Distance outside the tank's walls (Chebyshev, no top): 0.5 l0 -> wall, 1.5 and 2.5 l0 -> dummy.
    const double out = std::max({-f.x[i], f.x[i] - 0.1, -f.y[i], 0.0});
    if (f.kind[i] == kFluid) CHECK(out == 0.0);
    if (f.kind[i] == kWall) CHECK(out == Approx(0.5 * l0));
    if (f.kind[i] == kDummy) CHECK((out == Approx(1.5 * l0) || out == Approx(2.5 * l0)));
    CHECK(f.y[i] < 0.08);  // nothing above the walls' top: the tank is open
  }
  // Floor: 10 + 2 corner columns of 3 layers = 16 nodes per layer; sides up to 0.08 m (8 nodes per layer).
  CHECK(f.count(kWall) == 12 + 2 * 8);
  const MpsConstants k = lattice_constants(2, l0, 2.1 * l0);
  NeighborPairs nb;
  build_neighbors(f, k.re, Periodicity{}, nb);
  compute_number_density(f, nb, k.re);
  // The corner fluid node (0.005, 0.005) is surrounded by wall and dummy nodes: its n equals n0.
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && f.x[i] < 0.01 && f.y[i] < 0.01) CHECK(f.n[i] == Approx(k.n0).epsilon(1e-12));
}

TEST_CASE("periodic channel: every fluid node has the full-lattice number density, also at the periodic ends") {
  LiquidGeometry g;
  g.kind = LiquidGeometry::Kind::Channel;
  g.dim = 2;
  g.lo = {0, 0, 0};
  g.hi = {0.1, 0.05, 0};
  g.layers = 3;
  const double l0 = 0.01;
  FluidNodes f;
  generate_nodes(g, {FluidBlock{{0, 0, 0}, {0.1, 0.05, 0}}}, l0, f);
  CHECK(f.count(kFluid) == 50);
  CHECK(f.count(kWall) == 2 * 10);  // top and bottom plates, no walls at the periodic ends
  const MpsConstants k = lattice_constants(2, l0, 2.1 * l0);
  NeighborPairs nb;
  build_neighbors(f, k.re, g.periodicity(), nb);
  compute_number_density(f, nb, k.re);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] != kDummy) CHECK(f.n[i] == Approx(k.n0).epsilon(1e-12));
}

TEST_CASE("pipe: fluid within R at its block's velocity, wall nodes within l0 outside it, dummies beyond; periodic along x") {
  LiquidGeometry g;
  g.kind = LiquidGeometry::Kind::Pipe;
  g.dim = 3;
  g.center = {0, 0, 0};
  g.radius = 0.05;
  g.lo = {0, 0, 0};
  g.hi = {0.06, 0, 0};
  g.layers = 3;
  const double l0 = 0.01;
  FluidNodes f;
  generate_nodes(g, {FluidBlock{{0, -1, -1}, {0.06, 1, 1}, {2.0, 0, 0}}}, l0, f);
  std::size_t fluid = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double r = std::hypot(f.y[i], f.z[i]);
    CHECK(f.u[i] == (f.kind[i] == kFluid ? 2.0 : 0.0));  // the block's starting velocity; walls at rest
    CHECK((f.v[i] == 0.0 && f.w[i] == 0.0));
    if (f.kind[i] == kFluid) CHECK(r < 0.05);
    if (f.kind[i] == kWall) CHECK((r >= 0.05 - 1e-12 && r <= 0.06 + 1e-12));  // round-off of the lattice coordinates
    if (f.kind[i] == kDummy) CHECK((r > 0.06 && r <= 0.08 + 1e-12));
    CHECK((f.x[i] > 0 && f.x[i] < 0.06));
    fluid += f.kind[i] == kFluid;
  }
  // A node sits on the axis; integer (j, k) with j^2 + k^2 < 25, counted by hand per j = 0, +-1, +-2, +-3, +-4:
  // 9 + 2*9 + 2*9 + 2*7 + 2*5 = 69 per slice (pi R^2 / l0^2 = 78.5: the bore is resolved to within a layer), times
  // 6 slices along the periodic axis.
  CHECK(fluid == 69 * 6);
  CHECK(g.periodicity().axis == 0);
}

TEST_CASE("dummy pressure is the wall pressure plus the hydrostatic step rho g l0 per layer") {
  LiquidGeometry g;
  g.kind = LiquidGeometry::Kind::Tank;
  g.dim = 2;
  g.lo = {0, 0, 0};
  g.hi = {0.1, 0.05, 0};
  g.layers = 3;
  const double l0 = 0.01;
  FluidNodes f;
  generate_nodes(g, {}, l0, f);
  LiquidParams lp;
  lp.k = lattice_constants(2, l0, 2.1 * l0);
  lp.gravity = {0, -9.81, 0};
  NeighborPairs nb;
  build_neighbors(f, lp.k.re, Periodicity{}, nb);
  compute_number_density(f, nb, lp.k.re);
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kWall) f.p[i] = 500.0;
  extrapolate_dummy_pressure(f, nb, lp);
  // A dummy one layer below the middle of the floor: all its wall neighbours lie in the floor layer, exactly
  // one spacing above it, so its pressure is p_wall + rho g l0 to round-off.
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kDummy && std::abs(f.x[i] - 0.05) < 1e-9 + 0.005 && std::abs(f.y[i] + 0.015) < 1e-9)
      CHECK(f.p[i] == Approx(500.0 + 1000.0 * 9.81 * l0).epsilon(1e-12));
}
