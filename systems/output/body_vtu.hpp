// Composite grains for ParaView: one VTK XML UnstructuredGrid (.vtu) per frame, a cell per member,
// placed in the world. A member's cell is its core: a convex point set of the core's points (a hull's
// vertices; points on an ellipsoid's surface), which ParaView draws as their convex hull; a one-point
// core (a sphere) is a vertex and a two-point one (a capsule's axis) a line. The member's dilation
// radius, its body's id, shape, group and motion are cell fields: the core grown by `radius` is the
// member (Glyph a sphere of `radius` on a one-point core to see a sphere). Removed bodies are left out.
#pragma once

#include <string>
#include <vector>

#include "systems/bodies/bodies.hpp"

namespace gf {

// `shape` and `group` per body row.
std::string body_vtu_bytes(const Bodies& bodies, const Members& members, const std::vector<std::size_t>& shape,
                           const std::vector<int>& group);

}  // namespace gf
