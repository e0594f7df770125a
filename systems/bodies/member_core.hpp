// The convex core of a member of a composite grain (../shared/spec/002: a member is a convex core
// grown by a sphere of radius r), behind one seam. Every kind of core is stored as a few points in
// the member's frame (the Members table's CoreVertices, a shape's part), so the rigid moves from a
// shape's frame to a body's and on to the world, and the tables that hold them, treat every kind
// alike; what the points mean, and what the core answers, is the kind's:
//   hull       the convex hull of its points, 1 to kMaxCoreVertices (one point: a sphere's centre;
//              two: a capsule's axis; coplanar ones: a plate). Its support point along d is the
//              farthest point; a plane or a cylinder wall meets it at its points.
//   ellipsoid  four points: the centre c and the ends c + u_i of three orthogonal semi-axes; the
//              solid {c + [u_1 u_2 u_3] s : |s| <= 1}. A smooth core no list of points gives: its
//              support point along d is c + M M^T d / |M^T d|, M = [u_1 u_2 u_3] (ellipsoid_core.cpp).
// A kind answers: its support point along a direction (what GJK and MPR read, member_geometry.hpp),
// the centre and reach of a sphere holding it (the bounds the broadphase reads), the distance from a
// point to it (the voxels of the mass properties and the packing), and points whose convex hull
// draws it (the pictures). A new kind is its file of those functions, its row in member_core.cpp's
// table and its test; the contacts, the mass properties, the packing and the pictures take it from
// there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace gf {

enum class CoreKind : std::uint8_t { hull = 0, ellipsoid = 1 };

// A core as the seam reads it: its kind and its points in its own frame (three spans of equal length,
// structure of arrays like the Members table's CoreVertices).
struct CoreView {
  CoreKind kind = CoreKind::hull;
  std::span<const double> x, y, z;

  std::size_t size() const { return x.size(); }
  Eigen::Vector3d point(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

// A core prepared for many distance queries (the voxels of the mass properties and the packing).
class CoreSolid {
 public:
  virtual ~CoreSolid() = default;
  // The Euclidean distance from p to the core: 0 inside.
  virtual double distance(const Eigen::Vector3d& p) const = 0;
  // distance(p) <= r, possibly answered without the whole distance.
  virtual bool dilated_contains(const Eigen::Vector3d& p, double r) const { return distance(p) <= r; }
};

// One kind's answers (one row per kind in member_core.cpp).
struct CoreModel {
  std::string_view name;     // as a scene or a message names it
  std::size_t min_points = 1, max_points = 1;
  bool vertices = false;     // its support points are its points (a plane meets it at the lowest ones)
  // The core's point farthest along d (own frame; d need not be unit); for ties, the first point.
  Eigen::Vector3d (*support)(const CoreView& core, const Eigen::Vector3d& d) = nullptr;
  // A point inside the core and the largest distance from `centre` to the core (a bounding sphere).
  Eigen::Vector3d (*centre)(const CoreView& core) = nullptr;
  double (*reach)(const CoreView& core, const Eigen::Vector3d& centre) = nullptr;
  // The core prepared for distance queries.
  std::unique_ptr<CoreSolid> (*solid)(const CoreView& core) = nullptr;
  // Points whose convex hull draws the core (its own points; for a smooth core, points on its surface).
  std::vector<Eigen::Vector3d> (*outline)(const CoreView& core) = nullptr;
  // Throws std::invalid_argument when the points are not a core of this kind (a count out of range,
  // a non-finite point, semi-axes that are not orthogonal or not positive).
  void (*check)(const CoreView& core) = nullptr;
};

const CoreModel& core_model(CoreKind kind);

// The seam's calls, by the view's kind.
inline Eigen::Vector3d core_support(const CoreView& c, const Eigen::Vector3d& d) { return core_model(c.kind).support(c, d); }
inline Eigen::Vector3d core_centre(const CoreView& c) { return core_model(c.kind).centre(c); }
inline double core_reach(const CoreView& c, const Eigen::Vector3d& centre) { return core_model(c.kind).reach(c, centre); }
inline std::unique_ptr<CoreSolid> core_solid(const CoreView& c) { return core_model(c.kind).solid(c); }
inline std::vector<Eigen::Vector3d> core_outline(const CoreView& c) { return core_model(c.kind).outline(c); }
void check_core(const CoreView& c);  // check, with the kind's name in the message

// A view of points held as Eigen vectors (a shape's part), copied into structure of arrays.
struct CorePoints {
  std::vector<double> x, y, z;
  CoreKind kind = CoreKind::hull;
  CorePoints() = default;
  explicit CorePoints(std::span<const Eigen::Vector3d> points, CoreKind kind = CoreKind::hull);
  CoreView view() const { return {kind, x, y, z}; }
};

// The ellipsoid's functions (ellipsoid_core.cpp), for the table and the tests.
namespace ellipsoid_core {
Eigen::Vector3d support(const CoreView& core, const Eigen::Vector3d& d);
Eigen::Vector3d centre(const CoreView& core);
double reach(const CoreView& core, const Eigen::Vector3d& centre);
std::unique_ptr<CoreSolid> solid(const CoreView& core);
std::vector<Eigen::Vector3d> outline(const CoreView& core);
void check(const CoreView& core);
// The closest point of the ellipsoid's surface to p (Eberly, "Distance from a point to an ellipse, an
// ellipsoid, or a hyperellipsoid", 2013: the root of a monotone function of one variable by
// bisection); p itself when p is inside.
Eigen::Vector3d closest(const CoreView& core, const Eigen::Vector3d& p);
// The four points of the ellipsoid with semi-axes a, b, c along x, y, z, centred on the origin.
std::vector<Eigen::Vector3d> points(const Eigen::Vector3d& semi_axes);
}  // namespace ellipsoid_core

}  // namespace gf
