// Triangle meshes as walls: geometry only (the contacts are mesh_wall_contact.hpp's).
//   - STL files, binary and ASCII, read into a triangle soup that remembers where each triangle was
//     read (its facet's line, or its index in a binary file), so that a bad triangle is named.
//   - Primitive surfaces built without files: a rectangular plate, an annulus (an end ring with a
//     central hole) and a cylinder mantle.
//   - TriangleMesh: the soup welded into vertices, with per triangle its unit normal and the outward
//     in-plane normals of its edges, the edges with the triangles that share them, each vertex's
//     neighbours, and the flat regions (connected sets of coplanar triangles) that contact history
//     is keyed by.
//   - The closest point of a point on a triangle and the feature (face, edge, vertex) it lies on.
//   - TriangleGrid: a uniform grid over the mesh's reference (unrotated) frame listing, per cell,
//     the triangles within a reach of any point of the cell. The mesh is rigid, so the grid is built
//     once at load and a grain is looked up by its position carried into the reference frame.
//
// The STL reader of composite grains (systems/bodies/body_shapes.cpp) is not reused: it welds per
// solid, splits solids into convex parts and bounds a file to the few hundred triangles of a grain's
// hull; a wall's mesh is a plain triangle soup of up to millions of triangles.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "systems/walls/walls.hpp"

namespace gf {

// A mesh that cannot be used: what() is "<file>[:<line> | : triangle <k>]: <problem>. Fix: <fix>".
class MeshError : public std::runtime_error {
 public:
  explicit MeshError(const std::string& msg) : std::runtime_error(msg) {}
};

// Triangles as read: corners 3 t, 3 t + 1, 3 t + 2 of triangle t; at[t] is the line of its facet
// (ASCII) or its 1-based index (binary), for messages.
struct TriangleSoup {
  std::string name;     // the file, or the primitive, for messages
  bool binary = false;  // at[] counts triangles, not lines
  std::vector<Vec3d> corners;
  std::vector<std::size_t> at;
  std::size_t size() const { return at.size(); }
  void add(const Vec3d& a, const Vec3d& b, const Vec3d& c, std::size_t where) {
    corners.push_back(a), corners.push_back(b), corners.push_back(c);
    at.push_back(where);
  }
  // "<name>:<line>" or "<name>: triangle <k>".
  std::string where(std::size_t t) const;
};

// Files up to this size are read (a 1 GiB binary STL holds 21 million triangles).
inline constexpr std::size_t kMaxStlBytes = std::size_t{1} << 30;

// Reads an STL file: binary when its size is 84 + 50 n for the n its header states, else ASCII
// (`solid` ... `endsolid`, possibly several solids). Throws MeshError for a missing or unreadable
// file, a truncated binary file, a syntax error or a number that is not finite.
TriangleSoup read_stl(const std::filesystem::path& file);
TriangleSoup parse_stl(std::string_view bytes, const std::string& name);
// Writers, for tests and for exporting the primitives (binary: floats, as the format has).
void write_stl_binary(const std::filesystem::path& file, const TriangleSoup& soup);
void write_stl_ascii(const std::filesystem::path& file, const TriangleSoup& soup);

// Primitive surfaces (m). Each is a closed set of triangles sharing their vertices exactly.
// Plate: centre, unit normal, unit in-plane axis u (v = normal x u), half-widths along u and v, and
// the number of cells along each (each cell two triangles).
TriangleSoup plate_triangles(const Vec3d& center, const Vec3d& normal, const Vec3d& u, double half_u, double half_v,
                             int cells_u, int cells_v);
// Annulus in the plane through `center` normal to `axis`: radii inner < outer (inner 0: a disc, its
// triangles fanned from the centre), `segments` around.
TriangleSoup annulus_triangles(const Vec3d& center, const Vec3d& axis, double inner, double outer, int segments);
// Cylinder mantle: the surface at `radius` from the axis through `center`, `length` long (centred),
// `segments` around and `rings` along, closed around (its last column of cells shares the first's
// vertices). Its vertices lie on the cylinder; its flat facets lie inside it by at most
// radius (1 - cos(pi / segments)).
TriangleSoup cylinder_triangles(const Vec3d& center, const Vec3d& axis, double radius, double length, int segments,
                                int rings);

// A point on a triangle and the feature it lies on. Edge k runs from corner k to corner (k+1) % 3.
enum class Feature : std::uint8_t { Face, Edge0, Edge1, Edge2, Vertex0, Vertex1, Vertex2 };
inline bool is_edge(Feature f) { return f == Feature::Edge0 || f == Feature::Edge1 || f == Feature::Edge2; }
inline bool is_vertex(Feature f) { return f == Feature::Vertex0 || f == Feature::Vertex1 || f == Feature::Vertex2; }
inline int feature_index(Feature f) {
  return is_edge(f) ? static_cast<int>(f) - static_cast<int>(Feature::Edge0)
                    : (is_vertex(f) ? static_cast<int>(f) - static_cast<int>(Feature::Vertex0) : -1);
}

struct ClosestPoint {
  Vec3d q;
  Feature feature;
};

// The point of triangle (a, b, c) closest to p, by the regions of the triangle's Voronoi diagram in
// its plane (Ericson, Real-Time Collision Detection, 2005, section 5.1.5): a few dot products, no
// square root. A point on a region's boundary is given to the vertex, then the edge.
// Inline: the contact kernel calls it for every listed triangle near a grain, and a call returning
// the point through memory cost more than the arithmetic.
inline ClosestPoint closest_point_on_triangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {a, Feature::Vertex0};
  const Vec3d bp = p - b;
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return {b, Feature::Vertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return {a + (d1 / (d1 - d3)) * ab, Feature::Edge0};
  const Vec3d cp = p - c;
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return {c, Feature::Vertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return {a + (d2 / (d2 - d6)) * ac, Feature::Edge2};
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
    return {b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b), Feature::Edge1};
  const double denom = 1.0 / (va + vb + vc);
  return {a + (vb * denom) * ab + (vc * denom) * ac, Feature::Face};
}


struct TriangleMesh {
  std::string name;                            // for messages
  std::vector<Vec3d> vertex;                   // welded
  std::vector<std::array<std::uint32_t, 3>> tri;
  std::vector<std::size_t> at;                 // where each triangle was read (TriangleSoup::at)
  std::vector<Vec3d> normal;                   // unit, by the corners' order
  std::vector<Vec3d> centre;                   // centroid
  std::vector<double> bound;                   // m, the farthest corner's distance from the centroid
  // Per triangle and edge k: the unit vector in the triangle's plane, normal to the edge, pointing
  // away from the triangle, and the edge's index.
  std::vector<std::array<Vec3d, 3>> edge_out;
  std::vector<std::array<std::uint32_t, 3>> edge_of;
  // Per edge, the triangles that share it: edge_tri[edge_start[e] .. edge_start[e + 1]).
  std::vector<std::uint32_t> edge_start, edge_tri;
  // Per vertex, the other ends of its edges: vertex_nbr[vertex_start[v] .. vertex_start[v + 1]).
  std::vector<std::uint32_t> vertex_start, vertex_nbr;
  // Per triangle, its flat region: the connected set of coplanar triangles it belongs to (through
  // edges shared by exactly two triangles whose normals are parallel within 1e-9).
  std::vector<std::uint32_t> region;
  std::uint32_t regions = 0;
  Vec3d lo{0, 0, 0}, hi{0, 0, 0};  // bounding box
  double shortest_edge = 0;        // m

  std::size_t triangles() const { return tri.size(); }
  const Vec3d& corner(std::size_t t, int k) const { return vertex[tri[t][static_cast<std::size_t>(k)]]; }
};

// Welds the soup's corners (equal coordinates) into vertices and builds the adjacency. Refuses, with
// the triangle's place in the file, a soup without triangles, a corner that is not finite, and a
// degenerate triangle (area below 1e-12 of its longest edge squared: collinear or repeated corners).
TriangleMesh build_mesh(const TriangleSoup& soup);

// Applies x -> translate + scale x to a soup (in place).
void transform_soup(TriangleSoup& soup, double scale, const Vec3d& translate);

// Cells of edge h over the mesh's box grown by `reach`; cell c lists the triangles within reach of
// some point of c (tested as: distance from the cell's centre at most reach + half the cell's
// diagonal). A point outside the grid has no triangle within reach.
struct TriangleGrid {
  Vec3d lo{0, 0, 0};
  double h = 1, inv_h = 1;
  std::int64_t nx = 0, ny = 0, nz = 0;
  double reach = 0;
  std::vector<std::uint32_t> start;  // nx ny nz + 1
  std::vector<std::uint32_t> items;
  // One bit per cell, set where the cell lists a triangle: most grains sit in empty cells, and the
  // bits (1/32 of `start`) stay in cache where `start` would not.
  std::vector<std::uint64_t> occupied;
  std::span<const std::uint32_t> near(const Vec3d& p) const {
    const double fx = (p.x - lo.x) * inv_h, fy = (p.y - lo.y) * inv_h, fz = (p.z - lo.z) * inv_h;
    // Written so that NaN also falls out.
    if (!(fx >= 0 && fy >= 0 && fz >= 0 && fx < static_cast<double>(nx) && fy < static_cast<double>(ny) &&
          fz < static_cast<double>(nz)))
      return {};
    const auto c = static_cast<std::size_t>((static_cast<std::int64_t>(fz) * ny + static_cast<std::int64_t>(fy)) * nx +
                                            static_cast<std::int64_t>(fx));
    if (!((occupied[c >> 6] >> (c & 63)) & 1u)) return {};
    return {items.data() + start[c], items.data() + start[c + 1]};
  }
  std::size_t bytes() const {
    return (start.size() + items.size()) * sizeof(std::uint32_t) + occupied.size() * sizeof(std::uint64_t);
  }
};

// The grid for contacts of spheres up to radius `reach` (m). The cell edge is `reach`, coarsened
// where the box would need more than `max_cells` cells.
TriangleGrid build_triangle_grid(const TriangleMesh& mesh, double reach, std::size_t max_cells = std::size_t{1} << 22);

}  // namespace gf
