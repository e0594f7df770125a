// Still water tanks of a chosen size for the liquid benchmarks: a square (2D) or cubic (3D) block of side
// `side` nodes at l0 = 5 mm in a tank whose walls reach 1.5 times the water depth. The tank is stepped a few
// times first so the state (neighbours, free surface, pressures) is a running one, not the lattice.
#pragma once

#include <cstdio>
#include <map>
#include <memory>
#include <string>
#include <utility>

#include "systems/mps/liquid_simulation.hpp"

namespace gf::bench {

// `solver`: the keys of [liquid.solver], e.g. R"(kind = "eigen_cg")".
inline std::unique_ptr<LiquidSimulation> liquid_tank(int dim, int side,
                                                     const std::string& solver = R"(kind = "parallel_cg")",
                                                     int warm_steps = 5) {
  const double l0 = 0.005, L = side * l0;
  char text[1600];
  std::snprintf(text, sizeof text, R"(
[run]
dt = 5.0e-4
duration = 1.0
gravity = [0.0, -9.81, 0.0]
allow_unstable_dt = true
[liquid]
dim = %d
l0 = %.17g
density = 1000.0
viscosity = 1.0e-6
solver = { %s }
[geometry]
type = "tank"
lo = [0.0, 0.0, 0.0]
hi = [%.17g, %.17g, %.17g]
[[fluid]]
lo = [0.0, 0.0, 0.0]
hi = [%.17g, %.17g, %.17g]
)",
                dim, l0, solver.c_str(), L, 1.5 * L, dim == 3 ? L : 0.0, L, L, dim == 3 ? L : 0.0);
  auto sim = std::make_unique<LiquidSimulation>(LiquidSimulation::from_text(text));
  sim->advance(warm_steps);
  return sim;
}

// One running tank per (dim, side) with the default solver, made on first use and kept for the whole program.
inline LiquidSimulation& shared_liquid_tank(int dim, int side) {
  static std::map<std::pair<int, int>, std::unique_ptr<LiquidSimulation>> cache;
  auto& s = cache[{dim, side}];
  if (!s) s = liquid_tank(dim, side);
  return *s;
}

}  // namespace gf::bench
