// Mass, centre of mass and inertia of a composite grain of uniform density: the union of dilated
// convex polyhedra (core ⊕ sphere of radius r), members that may overlap, by the background-grid
// method of ../shared/spec/002: the union's bounding box is cut into cubic voxels of a given edge h,
// a voxel belongs to the body when its centre lies in at least one member (so overlaps count once),
// and the body's integrals are sums over those voxels. Each voxel is a uniform cube, so its own
// moment m_v h^2/6 about each axis is added to the point-mass sum: a voxel wholly inside the body
// then contributes its exact share of the second moments, and all the error comes from the voxels
// the surface cuts, which lie within (sqrt 3 / 2) h of it (the tests bound the errors this way).
// The principal axes come from Eigen's SelfAdjointEigenSolver on the inertia tensor.
//
// Point-in-member test: the exact Euclidean distance from the voxel centre to the convex core is at
// most r (its kind's CoreSolid, member_core.hpp; for a hull, ConvexCore). The core is given by its vertices only; its hull is found by brute force over
// vertex triples (a triple spans a boundary triangle when no vertex lies strictly on both sides of
// its plane): O(n^4) in the vertex count, which is negligible for the few-vertex cores of the
// seed's shapes (prisms, boxes, blocks), and refused above kMaxCoreVertices.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/member_core.hpp"

namespace gf {

inline constexpr std::size_t kMaxCoreVertices = 128;

// One member of a composite: its core's points in the composite's own (input) frame, and r.
struct DilatedPolyhedron {
  std::vector<Eigen::Vector3d> vertices;  // m, at least one: a hull's vertices, or the points of another kind
  double radius = 0;                      // m, >= 0
  CoreKind kind = CoreKind::hull;         // what the points are (member_core.hpp)
};

// The convex hull of a set of vertices, with the exact distance from a point to it. Degenerate
// hulls are exact too: one vertex (a point: the dilated member is a sphere), collinear vertices (a
// segment: a spherocylinder) and coplanar ones (a flat polygon: a dilated plate).
class ConvexCore {
 public:
  // Throws std::invalid_argument for no vertices, a non-finite one, or more than kMaxCoreVertices.
  explicit ConvexCore(std::vector<Eigen::Vector3d> vertices);

  // The Euclidean distance from p to the hull: 0 inside a solid core; outside it the smallest
  // distance to the hull's boundary triangles (Ericson, Real-Time Collision Detection, 2005, 5.1.5),
  // exact also where the closest point is an edge or a vertex, which face planes alone would miss.
  double distance(const Eigen::Vector3d& p) const;
  // distance(p) <= r, the face planes first: inside all of them is inside, beyond one by more
  // than r is outside; only points within r of the hull outside it reach the triangles.
  bool dilated_contains(const Eigen::Vector3d& p, double r) const;

  std::size_t face_planes() const { return planes_.size(); }   // distinct; 0 unless solid
  std::size_t triangles() const { return triangles_.size(); }  // boundary triangles

 private:
  struct Plane {
    Eigen::Vector3d n;  // outward unit normal
    double d;           // n . x <= d inside
  };
  void build_triangles();
  double max_plane_excess(const Eigen::Vector3d& p) const;
  double distance_to_boundary(const Eigen::Vector3d& p) const;

  std::vector<Eigen::Vector3d> v_;  // the vertices; the two ends when the core is a segment
  std::vector<Plane> planes_;
  std::vector<std::array<std::uint32_t, 3>> triangles_;
  bool segment_ = false;
};

struct MassProperties {
  double volume = 0, mass = 0;          // m^3, kg
  Eigen::Vector3d centre;               // m, centre of mass in the input frame
  Eigen::Matrix3d inertia;              // kg m^2, about the centre, input-frame axes
  Eigen::Vector3d moments;              // kg m^2, principal moments, ascending
  Eigen::Matrix3d axes;                 // columns: the principal axes in the input frame (det +1)
  std::size_t voxels = 0;               // voxels counted inside
  std::array<std::size_t, 3> grid{};    // voxels along x, y, z of the input frame
  double voxel = 0;                     // m, the edge used
};

// The background-grid mass properties of the union of `members` at density rho (kg/m^3) with voxel
// edge h (m). The grid spans the union's bounding box (the cores' vertex box grown by r), whole
// voxels centred on it. Throws std::invalid_argument for no members, rho or h not positive and
// finite, or a grid of more than 2^22 voxels.
MassProperties voxel_mass_properties(std::span<const DilatedPolyhedron> members, double rho, double h);

// The mass properties of one ellipsoid with semi-axes (a, b, c) along x, y, z, centred on the origin,
// at density rho, exact: volume 4/3 pi a b c, moments m (b^2 + c^2)/5, m (a^2 + c^2)/5, m (a^2 + b^2)/5
// (ellipsoid_core.cpp). Throws std::invalid_argument for a semi-axis or rho not positive and finite.
MassProperties ellipsoid_mass_properties(const Eigen::Vector3d& semi_axes, double rho);

// The mass properties of one sphere of `radius` at density rho, exact (no voxel grid is needed): mass rho 4/3 pi r^3, every principal moment 2/5 m r^2, the axes the input frame's.
MassProperties sphere_mass_properties(double radius, double rho);

// The members' rows in the body frame of `props` (origin at the centre of mass, axes the principal
// axes: x_body = axes^T (x - centre)), each naming body row `body`.
std::vector<MemberRow> body_frame_members(std::span<const DilatedPolyhedron> members, const MassProperties& props,
                                          std::uint32_t body);

// A body at rest with the mass and principal moments of `props`, its centre of mass at `x` (world,
// m) and its input frame turned by `frame` into the world: orientation frame * quaternion(axes).
BodyRow body_row(const MassProperties& props, const Eigen::Vector3d& x,
                 const Eigen::Quaterniond& frame = Eigen::Quaterniond::Identity());

}  // namespace gf
