// Koshizuka & Oka's particle collision model (Koshizuka, Nobe & Oka 1998; used by most MPS codes against
// clustering and wall penetration): a fluid node closer than `distance` to another node and approaching it gets
// an impulse that removes the approaching normal velocity, with restitution e:
//   fluid-fluid (equal masses):  du_i = -(1 + e)/2 w n,   fluid-wall/dummy (wall fixed): du_i = -(1 + e) w n,
//   w = (u_i - u_j).n > 0, n = (r_j - r_i)/|r_j - r_i|; then r_i += dt du_i.
// All impulses of a step are computed from the velocities before it (Jacobi), so the result does not depend on
// the order of rows or threads. Off when distance = 0.
// Reads: FluidNodes x, y, z, u, v, w, kind; NeighborPairs. Writes: FluidNodes u, v, w, x, y, z, ax, ay, az.
#pragma once

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

struct CollisionSettings {
  double distance = 0;     // m, 0: off
  double restitution = 0.2;
};

// Returns the number of colliding pairs seen from fluid rows.
std::size_t apply_collisions(FluidNodes& f, const NeighborPairs& nb, const CollisionSettings& c, double dt);

}  // namespace gf
