// The walls as surfaces for ParaView: every analytic wall and mesh wall at a time t, placed as the
// contacts place them (turned and carried by their motion), as one triangle soup with each triangle's
// wall index (analytic walls in scene order, then the meshes: the order of walls.csv).
//  - a plane with an outline (a box's face, a drum's end) is that polygon; a plane without one is
//    drawn where it crosses the scene's box;
//  - a cylinder is its mantle over its length (a drum's), or over the scene's box along its axis;
//  - a mesh is its triangles.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

struct SceneBox {
  Vec3d lo{0, 0, 0}, hi{0, 0, 0};
};

struct WallSurface {
  std::vector<Vec3d> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::int32_t> wall;  // per triangle
};

// The box the unbounded walls are drawn across: the grains' bounding box, the finite walls (outlines,
// drums, meshes) and a point of each unbounded plane at their reference place, grown by a tenth of its
// largest side on every side.
SceneBox scene_box(const Grains& g, const Walls& walls, const MeshWalls* meshes);
// The same around `points` (composite grains' centres) instead of the grains.
SceneBox scene_box(const std::vector<Vec3d>& points, const Walls& walls, const MeshWalls* meshes);

// The walls and meshes placed at time t (as Walls::place places them).
WallSurface wall_surface(const Walls& walls, const MeshWalls* meshes, double t, const SceneBox& box);

// A .vtp document of the surface: its triangles as polygons with the cell array "wall".
std::string wall_surface_vtp(const WallSurface& s);

// Whether any wall or mesh moves (turns or translates), so that its surface changes between frames.
bool walls_move(const Walls& walls, const MeshWalls* meshes);

}  // namespace gf
