#include "systems/bodies/mass_properties.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

namespace gf {

namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

// Ericson (2005), Real-Time Collision Detection, 5.1.5: the point of triangle abc closest to p, by
// the Voronoi region of p (vertex, edge or face) found from barycentric dot products.
Vector3d closest_on_triangle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double distance_to_segment(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double t = std::clamp(ab.dot(p - a) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

void check_vertices(const std::vector<Vector3d>& v) {
  if (v.empty()) throw std::invalid_argument("a convex core needs at least one vertex");
  if (v.size() > kMaxCoreVertices)
    throw std::invalid_argument("a convex core has " + std::to_string(v.size()) + " vertices, more than the " +
                                std::to_string(kMaxCoreVertices) + " its brute-force hull accepts");
  for (const Vector3d& x : v)
    if (!x.allFinite()) throw std::invalid_argument("a convex core's vertex is not finite");
}

// The length scale of a vertex set (its bounding box's largest edge), for round-off tolerances.
double largest_edge(const std::vector<Vector3d>& v) {
  Vector3d lo = v.front(), hi = v.front();
  for (const Vector3d& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  return (hi - lo).maxCoeff();
}

}  // namespace

ConvexCore::ConvexCore(std::vector<Vector3d> vertices) : v_(std::move(vertices)) {
  check_vertices(v_);
  const double tol = 1e-9 * largest_edge(v_);
  std::size_t ia = 0, ib = 0;
  for (std::size_t i = 0; i < v_.size(); ++i)
    for (std::size_t j = i + 1; j < v_.size(); ++j)
      if ((v_[i] - v_[j]).squaredNorm() > (v_[ia] - v_[ib]).squaredNorm()) ia = i, ib = j;
  if (ia == ib || (v_[ia] - v_[ib]).norm() <= tol) {  // every vertex at one point
    v_.resize(1);
    return;
  }
  const Vector3d a = v_[ia], b = v_[ib];
  const bool collinear = std::all_of(v_.begin(), v_.end(), [&](const Vector3d& x) {
    return distance_to_segment(x, a, b) <= tol;
  });
  if (collinear) {
    v_ = {a, b};
    segment_ = true;
    return;
  }
  build_triangles();
}

// Every vertex triple whose plane leaves no vertex strictly on both sides is a boundary triangle (on
// a face with more than three vertices, several overlapping ones, which cover the face exactly). A
// vertex strictly inside gives the face's outward normal; when none is off any such plane the core
// is flat, has no inside and no planes, and its triangles cover the polygon.
void ConvexCore::build_triangles() {
  const double scale = largest_edge(v_), tol = 1e-9 * scale;
  const std::uint32_t n = static_cast<std::uint32_t>(v_.size());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = i + 1; j < n; ++j)
      for (std::uint32_t k = j + 1; k < n; ++k) {
        const Vector3d normal = (v_[j] - v_[i]).cross(v_[k] - v_[i]);
        if (normal.norm() <= tol * scale) continue;  // collinear triple
        const Vector3d u = normal.normalized();
        const double d = u.dot(v_[i]);
        std::size_t above = 0, below = 0;
        for (const Vector3d& x : v_) {
          const double s = u.dot(x) - d;
          above += s > tol, below += s < -tol;
        }
        if (above > 0 && below > 0) continue;
        triangles_.push_back({i, j, k});
        if (above + below == 0) continue;  // flat core
        const Plane pl = above > 0 ? Plane{-u, -d} : Plane{u, d};
        const bool known = std::any_of(planes_.begin(), planes_.end(), [&](const Plane& q) {
          return (q.n - pl.n).norm() <= 1e-9 && std::abs(q.d - pl.d) <= tol;
        });
        if (!known) planes_.push_back(pl);
      }
}

double ConvexCore::max_plane_excess(const Vector3d& p) const {
  double e = -std::numeric_limits<double>::infinity();
  for (const Plane& pl : planes_) e = std::max(e, pl.n.dot(p) - pl.d);
  return e;
}

double ConvexCore::distance_to_boundary(const Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : triangles_)
    best = std::min(best, (p - closest_on_triangle(p, v_[t[0]], v_[t[1]], v_[t[2]])).squaredNorm());
  return std::sqrt(best);
}

double ConvexCore::distance(const Vector3d& p) const {
  if (triangles_.empty()) return segment_ ? distance_to_segment(p, v_[0], v_[1]) : (p - v_[0]).norm();
  if (!planes_.empty() && max_plane_excess(p) <= 0.0) return 0.0;
  return distance_to_boundary(p);
}

bool ConvexCore::dilated_contains(const Vector3d& p, double r) const {
  if (planes_.empty()) return distance(p) <= r;
  const double e = max_plane_excess(p);
  if (e <= 0.0) return true;
  if (e > r) return false;  // a face plane supports the core, so the distance is at least e
  return distance_to_boundary(p) <= r;
}

namespace {

// A member as the voxel loop reads it: its core and a sphere holding it (for a cheap rejection).
struct VoxelShape {
  std::unique_ptr<CoreSolid> core;
  double r;
  Vector3d centre;
  double bound2;  // squared radius of the bounding sphere
};

VoxelShape member_shape(const DilatedPolyhedron& m) {
  if (!std::isfinite(m.radius) || m.radius < 0.0)
    throw std::invalid_argument("a member's dilation radius must be finite and not negative");
  const CorePoints points(m.vertices, m.kind);
  if (m.kind != CoreKind::hull) check_core(points.view());
  std::unique_ptr<CoreSolid> core = core_solid(points.view());
  const Vector3d c = core_centre(points.view());
  const double bound = core_reach(points.view(), c) + m.radius;
  return {std::move(core), m.radius, c, bound * bound * (1.0 + 1e-12)};
}

// The box holding a member's core: its points' for a hull, its support points along the axes for
// another kind.
void grow_box(const DilatedPolyhedron& m, Vector3d& lo, Vector3d& hi) {
  const Vector3d r = Vector3d::Constant(m.radius);
  if (m.kind == CoreKind::hull) {
    for (const Vector3d& x : m.vertices) lo = lo.cwiseMin(x - r), hi = hi.cwiseMax(x + r);
    return;
  }
  const CorePoints points(m.vertices, m.kind);
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::min(lo[a], core_support(points.view(), -Vector3d::Unit(a))[a] - m.radius);
    hi[a] = std::max(hi[a], core_support(points.view(), Vector3d::Unit(a))[a] + m.radius);
  }
}

// The union's voxels: n[k] cubes of edge h along each axis, centred on the bounding box's middle.
struct Grid {
  Vector3d mid, origin;  // m: the box's middle, the grid's low corner
  std::array<std::size_t, 3> n{};
  double h = 0;
  Vector3d centre(std::size_t i, std::size_t j, std::size_t k) const {
    return origin + h * Vector3d(i + 0.5, j + 0.5, k + 0.5);
  }
};

Grid make_grid(std::span<const DilatedPolyhedron> members, double h) {
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const DilatedPolyhedron& m : members) grow_box(m, lo, hi);
  Grid g;
  g.h = h;
  g.mid = 0.5 * (lo + hi);
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double cells = std::max(1.0, std::ceil((hi[a] - lo[a]) / h));
    total *= cells;
    // 2^22 voxels (160 along each axis of a cube): counting costs about a second per million voxels, and the
    // input fuzzer found a grid ten times finer than a scene's taking a minute (2^31 was the bound before).
    if (!(total <= 4194304.0))
      throw std::invalid_argument("the voxel edge " + std::to_string(h) + " m makes more than 2^22 voxels");
    g.n[a] = static_cast<std::size_t>(cells);
  }
  g.origin = g.mid - 0.5 * h * Vector3d(g.n[0], g.n[1], g.n[2]);
  return g;
}

bool covered(const std::vector<VoxelShape>& shapes, const Vector3d& p) {
  for (const VoxelShape& s : shapes)
    if ((p - s.centre).squaredNorm() <= s.bound2 && s.core->dilated_contains(p, s.r)) return true;
  return false;
}

// Sums over the voxels inside, positions relative to the grid's middle (less cancellation).
struct Sums {
  std::size_t count = 0;
  Vector3d first = Vector3d::Zero();   // sum of x
  Matrix3d second = Matrix3d::Zero();  // sum of x x^T
  void add(const Sums& o) { count += o.count, first += o.first, second += o.second; }
};

Sums slice_sums(const std::vector<VoxelShape>& shapes, const Grid& g, std::size_t k) {
  Sums s;
  for (std::size_t j = 0; j < g.n[1]; ++j)
    for (std::size_t i = 0; i < g.n[0]; ++i) {
      const Vector3d p = g.centre(i, j, k);
      if (!covered(shapes, p)) continue;
      const Vector3d x = p - g.mid;
      ++s.count, s.first += x, s.second += x * x.transpose();
    }
  return s;
}

// Each z-slice summed on its own, then the slices in order: the result does not depend on threads.
Sums voxel_sums(const std::vector<VoxelShape>& shapes, const Grid& g) {
  std::vector<Sums> slices(g.n[2]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.n[2]), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) slices[k] = slice_sums(shapes, g, k);
  });
  Sums total;
  for (const Sums& s : slices) total.add(s);
  return total;
}

// Ascending moments; axes made deterministic (each of the first two with its largest component
// positive) and right-handed (the third their cross product).
void principal_axes(MassProperties& p) {
  const Eigen::SelfAdjointEigenSolver<Matrix3d> es(p.inertia);
  p.moments = es.eigenvalues();
  Matrix3d axes = es.eigenvectors();
  for (int a = 0; a < 2; ++a) {
    Eigen::Index big = 0;
    axes.col(a).cwiseAbs().maxCoeff(&big);
    if (axes(big, a) < 0) axes.col(a) = -axes.col(a);
  }
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  p.axes = axes;
}

}  // namespace

MassProperties voxel_mass_properties(std::span<const DilatedPolyhedron> members, double rho, double h) {
  if (members.empty()) throw std::invalid_argument("a composite needs at least one member");
  if (!std::isfinite(rho) || rho <= 0.0) throw std::invalid_argument("the density must be positive and finite");
  if (!std::isfinite(h) || h <= 0.0) throw std::invalid_argument("the voxel edge must be positive and finite");
  std::vector<VoxelShape> shapes;
  for (const DilatedPolyhedron& m : members) shapes.push_back(member_shape(m));
  const Grid g = make_grid(members, h);
  const Sums s = voxel_sums(shapes, g);
  MassProperties p;
  p.voxel = h, p.grid = g.n, p.voxels = s.count;
  const double cell = h * h * h;
  p.volume = static_cast<double>(s.count) * cell;
  p.mass = rho * p.volume;
  if (s.count == 0) throw std::invalid_argument("no voxel centre lies in the composite: make the voxel edge smaller");
  const Vector3d c = s.first / static_cast<double>(s.count);
  p.centre = g.mid + c;
  // Second moments about the centre, each voxel a uniform cube (its own h^2/12 per axis).
  const Matrix3d second = cell * s.second - p.volume * c * c.transpose() + p.volume * h * h / 12.0 * Matrix3d::Identity();
  p.inertia = rho * (second.trace() * Matrix3d::Identity() - second);
  principal_axes(p);
  return p;
}

std::vector<MemberRow> body_frame_members(std::span<const DilatedPolyhedron> members, const MassProperties& props,
                                          std::uint32_t body) {
  std::vector<MemberRow> rows;
  for (const DilatedPolyhedron& m : members) {
    MemberRow row{body, {}, m.radius, static_cast<std::uint8_t>(m.kind)};
    for (const Vector3d& x : m.vertices) {
      const Vector3d b = props.axes.transpose() * (x - props.centre);
      row.vertices.push_back({b.x(), b.y(), b.z()});
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

BodyRow body_row(const MassProperties& props, const Vector3d& x, const Eigen::Quaterniond& frame) {
  const Eigen::Quaterniond q = (frame * Eigen::Quaterniond(props.axes)).normalized();
  BodyRow row;
  row.x = {x.x(), x.y(), x.z()};
  row.q = {q.w(), q.x(), q.y(), q.z()};
  row.mass = props.mass;
  row.inertia = {props.moments[0], props.moments[1], props.moments[2]};
  return row;
}

MassProperties sphere_mass_properties(double radius, double rho) {
  if (!(std::isfinite(radius) && radius > 0.0 && std::isfinite(rho) && rho > 0.0))
    throw std::invalid_argument("a sphere's radius and density must be positive and finite");
  MassProperties m;
  m.volume = 4.0 / 3.0 * std::numbers::pi * radius * radius * radius;
  m.mass = rho * m.volume;
  m.centre = Eigen::Vector3d::Zero();
  m.inertia = 0.4 * m.mass * radius * radius * Eigen::Matrix3d::Identity();
  m.moments = Eigen::Vector3d::Constant(0.4 * m.mass * radius * radius);
  m.axes = Eigen::Matrix3d::Identity();
  return m;
}

}  // namespace gf
