// The contact systems of a scene of grains, assembled in one place for every model that has grains
// (one process, ranks, grains in a liquid): the pair contacts of the scene's law, and the analytic
// and mesh walls' contacts where the scene has such walls.
#pragma once

#include <string_view>

namespace gf {

class Schedule;

// Which contacts a scene needs: its law's name ([contact] model) and whether it has analytic walls
// and mesh walls.
struct ContactNeeds {
  std::string_view law;
  bool walls = false;
  bool meshes = false;
};

// Adds PairContact<Law>, then WallContact<Law> and MeshWallContact<Law> where needed, to `step`.
// Throws std::invalid_argument naming the law when no registered law has that name.
void add_contact_systems(Schedule& step, const ContactNeeds& needs);

}  // namespace gf
