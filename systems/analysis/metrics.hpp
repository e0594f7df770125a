// Whole-system measures written to series.csv and summary.json. Sums are deterministic
// (parallel_deterministic_reduce), so two runs with the same thread count print the same digits.
#pragma once

#include <cstdint>

#include "engine/grains.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

struct Energies {
  double translational = 0.0;  // J
  double rotational = 0.0;     // J
};
Energies kinetic_energy(const Grains& g);
// Gravitational potential energy relative to the origin, -m g.x summed (J).
double potential_energy(const Grains& g, double gx, double gy, double gz);

struct ContactStats {
  std::int64_t pair_contacts = 0;
  std::int64_t wall_contacts = 0;
  double max_overlap_ratio = 0.0;  // largest overlap / smaller diameter of the two (wall: own diameter)
  bool finite = true;              // every position and velocity finite
};
ContactStats contact_stats(const Grains& g, const NeighborList& list, const Walls& walls);
// Adds the owned grains' contacts with mesh walls (at their angle for time t) to `s`: the merged
// contacts whose closest point lies within the grain's radius, and their overlaps.
void add_mesh_contacts(ContactStats& s, const Grains& g, const MeshWalls& walls, double t, bool rotation_enabled);

// Danckwerts' intensity of segregation of species `type_a` against the rest: the standard
// deviation of the local volume fraction of type_a over cubic cells of edge `cell` (m), weighted
// by each cell's solid volume, divided by sqrt(p (1 - p)) with p the global fraction. 0 for a
// perfect mixture at the cell scale (a random mixture gives a small positive floor), 1 when every
// cell holds one species only. Cells with less than `min_grains` grains are left out.
double segregation_index(const Grains& g, std::int32_t type_a, double cell, int min_grains = 4);

}  // namespace gf
