// The scene keys of a mesh wall: a [[wall]] of type "mesh".
//   file = "drum.stl"           an STL file (binary or ASCII), relative to the scene file; or
//   primitive = "plate"         a surface built without a file:
//     plate:    center, normal, axis (an in-plane direction), half_widths = [a, b] (m, along axis and
//               normal x axis), cells = [n_a, n_b] (default [1, 1], two triangles per cell)
//     annulus:  center, axis, inner_radius (m, 0 for a disc), outer_radius (m), segments (default 64)
//     cylinder: center, axis, radius, length (m), segments (default 64), rings (default 1): the mantle
//   scale = 1.0                 applied to the file's coordinates (0.001 for a file in mm), then
//   translate = [0, 0, 0]       added (m); both for files only
//   omega = 0.0                 rad/s, the rigid rotation about rotation_axis through rotation_point
//   rotation_axis, rotation_point   default: a primitive's axis (a plate's normal) and centre; a
//                               file that turns must give both
// Several mesh walls with the same axis, point and omega turn together (a mixer of plates and rings).
#pragma once

#include <string>

#include "engine/scene.hpp"
#include "systems/walls/mesh_wall_contact.hpp"

namespace gf {

// Reads the [[wall]] table `w` (its type already "mesh") as a wall named `name`. The grid's reach is
// the largest grain radius; a surface whose fastest point moves more than 0.1 of the smallest
// diameter per step dt is refused. Throws SceneError naming the scene file, line, key and fix (for
// an unusable mesh file also its own line or triangle).
MeshWall read_mesh_wall(const SceneNode& w, const std::string& name, double largest_radius, double smallest_diameter,
                        double dt);

// The mesh wall that a sphere at p of radius r overlaps, or null (for the fills' checks).
const MeshWall* overlapped_mesh_wall(const MeshWalls& walls, const Vec3d& p, double r);

}  // namespace gf
