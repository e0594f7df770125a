// Free-surface detection (systems/mps/free_surface.hpp): a node below beta n0 is a surface node; in a
// locally averaged liquid the test reads beta eps n0; a closed liquid (liquid.free_surface = false) has none.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "mps_support.hpp"
#include "systems/mps/free_surface.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/number_density.hpp"

using namespace gf;

namespace {

// The still 2D tank's nodes with their number densities, and a fluid node of its interior at n0.
std::size_t interior_node(LiquidSimulation& sim) {
  FluidNodes& f = sim.nodes();
  LiquidParams& lp = sim.params();
  NeighborPairs nb;
  test::prepare_nodes(sim, nb);
  std::size_t interior = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && !f.surface[i] && std::abs(f.n[i] / lp.k.n0 - 1.0) < 1e-9) interior = i;
  return interior;
}

}  // namespace

TEST_CASE("free surface: below beta n0, or beta eps n0 in an averaged liquid; none in a closed liquid") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("hydrostatic_2d.toml"));
  FluidNodes& f = sim.nodes();
  LiquidParams& lp = sim.params();
  const std::size_t interior = interior_node(sim);
  REQUIRE(f.kind[interior] == kFluid);
  const std::size_t top = detect_free_surface(f, lp);
  CHECK(top > 0);  // the tank's top row and the walls above the liquid
  CHECK(!f.surface[interior]);
  // Thinned to 0.9 n0: a surface node in clear liquid (0.9 < beta = 0.97), not where eps = 0.8
  // (0.9 > 0.97 x 0.8).
  f.n[interior] = 0.9 * lp.k.n0;
  CHECK(detect_free_surface(f, lp) == top + 1);
  CHECK(f.surface[interior]);
  const std::vector<double> thin(f.size(), 0.8);
  detect_free_surface(f, lp, thin);
  CHECK(!f.surface[interior]);
  // Closed: no surface node at all, the thinned one included.
  lp.free_surface = false;
  CHECK(detect_free_surface(f, lp) == 0);
  CHECK(!f.surface[interior]);
}

TEST_CASE("free surface: liquid.free_surface is read from the scene, true by default") {
  CHECK(LiquidSimulation::from_file(test::liquid_scene("hydrostatic_2d.toml")).params().free_surface);
  const std::string closed = test::read_file(test::liquid_scene("poiseuille_2d.toml"));
  std::string text = closed;
  text.replace(text.find("[liquid]"), 8, "[liquid]\nfree_surface = false");
  CHECK(!LiquidSimulation::from_text(text).params().free_surface);
}
