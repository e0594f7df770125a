// The ellipsoid core (systems/bodies/ellipsoid_core.cpp, member_core.hpp): its support function,
// closest point and mass properties against analytic values, and the contacts member_geometry.hpp
// builds on it against independent computations: two ellipsoids' distance by alternating projections,
// the depth of equal-axis "ellipsoids" (spheres) and of ellipsoids meeting along an axis, a plane's and
// a drum mantle's overlap from the support function's closed form.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_shapes.hpp"
#include "systems/bodies/mass_properties.hpp"
#include "systems/bodies/member_core.hpp"
#include "systems/bodies/member_geometry.hpp"

using Eigen::Matrix3d;
using Eigen::Vector3d;
using Catch::Matchers::Contains;

namespace {

// An ellipsoid of semi-axes `axes` turned by `turn` about its centre `c` (the points of member_core.hpp).
gf::CorePoints ellipsoid(const Vector3d& axes, const Matrix3d& turn = Matrix3d::Identity(),
                         const Vector3d& c = Vector3d::Zero()) {
  std::vector<Vector3d> p = gf::ellipsoid_core::points(axes);
  for (Vector3d& x : p) x = c + turn * x;
  return gf::CorePoints(p, gf::CoreKind::ellipsoid);
}

Matrix3d turn(double angle, const Vector3d& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

// The closed form of the support: h(d) = d.c + |M^T d|, M's columns the semi-axis vectors.
double support_height(const Vector3d& axes, const Matrix3d& r, const Vector3d& c, const Vector3d& d) {
  const Matrix3d m = r * axes.asDiagonal();
  return d.dot(c) + (m.transpose() * d).norm();
}

}  // namespace

TEST_CASE("ellipsoid core: the support point is on the surface and reaches the closed form's height") {
  const Vector3d axes(0.003, 0.002, 0.001), c(0.01, -0.02, 0.005);
  const Matrix3d r = turn(0.7, {1, 2, 3});
  const gf::CorePoints e = ellipsoid(axes, r, c);
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0, 1);
  for (int k = 0; k < 200; ++k) {
    const Vector3d d(n(rng), n(rng), n(rng));
    const Vector3d p = gf::core_support(e.view(), d);
    const Vector3d q = r.transpose() * (p - c);
    // On the surface to round-off, and as high along d as the closed form (both exact in doubles).
    CHECK(q.cwiseQuotient(axes).squaredNorm() == Approx(1.0).epsilon(1e-12));
    CHECK(d.dot(p) == Approx(support_height(axes, r, c, d)).epsilon(1e-12));
  }
  CHECK((gf::core_centre(e.view()) - c).norm() == 0.0);
  CHECK(gf::core_reach(e.view(), c) == Approx(0.003).epsilon(1e-12));
}

TEST_CASE("ellipsoid core: the closest point meets the surface along its normal, and inside is distance 0") {
  const Vector3d axes(0.004, 0.0025, 0.001);
  const Matrix3d r = turn(-1.1, {0, 1, 1});
  const gf::CorePoints e = ellipsoid(axes, r);
  const auto solid = gf::core_solid(e.view());
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-0.008, 0.008);
  int outside = 0;
  for (int k = 0; k < 300; ++k) {
    const Vector3d p(u(rng), u(rng), u(rng));
    const Vector3d x = gf::ellipsoid_core::closest(e.view(), p);
    const Vector3d q = r.transpose() * p, qx = r.transpose() * x;
    if (q.cwiseQuotient(axes).squaredNorm() <= 1.0) {
      CHECK(solid->distance(p) == 0.0);
      continue;
    }
    ++outside;
    // On the surface; p - x along the surface's normal there (the gradient q_i / a_i^2): their cross
    // product vanishes to the bisection's round-off (a relative 1e-9 is far above it).
    CHECK(qx.cwiseQuotient(axes).squaredNorm() == Approx(1.0).epsilon(1e-10));
    const Vector3d normal = qx.cwiseQuotient(axes.cwiseProduct(axes)).normalized();
    CHECK((q - qx).normalized().cross(normal).norm() < 1e-9);
    CHECK(solid->distance(p) == Approx((p - x).norm()).epsilon(1e-12));
  }
  CHECK(outside > 100);
}

TEST_CASE("ellipsoid core: two ellipsoids' distance matches alternating projections") {
  // Alternating projections between two disjoint convex sets (Cheney and Goldstein 1959) converge to
  // a pair of closest points: an algorithm independent of GJK's support points.
  const Vector3d axes_a(0.003, 0.002, 0.0015), axes_b(0.0025, 0.0025, 0.001);
  const Matrix3d ra = turn(0.4, {1, 0, 1}), rb = turn(2.0, {0.3, 1, -0.5});
  for (const Vector3d& cb : {Vector3d(0.007, 0.001, 0.0), Vector3d(0.002, 0.006, -0.002), Vector3d(0.003, 0.003, 0.004)}) {
    const gf::CorePoints a = ellipsoid(axes_a, ra), b = ellipsoid(axes_b, rb, cb);
    Vector3d pa = Vector3d::Zero(), pb = cb;
    for (int it = 0; it < 200000; ++it) {
      const Vector3d na = gf::ellipsoid_core::closest(a.view(), pb);
      const Vector3d nb = gf::ellipsoid_core::closest(b.view(), na);
      const bool still = (na - pa).norm() < 1e-16 && (nb - pb).norm() < 1e-16;
      pa = na, pb = nb;
      if (still) break;
    }
    const double d = (pb - pa).norm();
    REQUIRE(d > 0.0005);
    // Dilated enough that the bounding spheres overlap, so GJK runs (the cores' distance is r's alone).
    const gf::MemberShape sa = gf::world_member(a, 0.003, Vector3d::Zero());
    const gf::MemberShape sb = gf::world_member(b, 0.003, cb);
    const gf::MemberContact c = gf::member_member(sa, sb);
    CHECK(c.kind == gf::MemberProximity::separated);
    // GJK stops within 1e-12 of the pair's size (about 1e-14 m here), the projections at 1e-16 m:
    // 1e-12 m is far above both and far below a contact's overlaps.
    CHECK(c.core_distance == Approx(d).margin(1e-12));
    // The distance is stationary along the surfaces, so a stop at a gap eps leaves the closest points
    // up to sqrt(2 eps rho) astray across it (rho the surfaces' radius of curvature, about 1 mm): the
    // normal to about sqrt(2 eps / rho), 5e-6 rad for eps = 1e-14 m.
    CHECK((c.n - (pb - pa) / d).norm() < 1e-5);
  }
}

TEST_CASE("ellipsoid core: overlapping cores' depth, for spheres and for ellipsoids meeting along an axis") {
  // Equal semi-axes make spheres: the overlap is R_a + R_b - D whatever the turn.
  const gf::CorePoints a = ellipsoid(Vector3d::Constant(0.002), turn(0.3, {1, 1, 0}));
  const gf::CorePoints b = ellipsoid(Vector3d::Constant(0.0015), turn(1.3, {0, 1, 1}), Vector3d(0.003, 0.0, 0.0));
  const gf::MemberContact c = gf::member_member(gf::world_member(a, 0.0, Vector3d::Zero()),
                                                gf::world_member(b, 0.0, Vector3d(0.003, 0, 0)));
  CHECK(c.kind == gf::MemberProximity::penetrating);
  CHECK(c.delta == Approx(0.0005).margin(1e-11));
  CHECK((c.n - Vector3d::UnitX()).norm() < 1e-6);
  // Axis-aligned ellipsoids on the x axis, the x semi-axes the shortest: the depth along x, a_A + a_B - D,
  // is the least by symmetry; both orders agree.
  const gf::CorePoints e = ellipsoid({0.001, 0.004, 0.003}), f = ellipsoid({0.0015, 0.003, 0.005}, Matrix3d::Identity(),
                                                                          Vector3d(0.0022, 0, 0));
  const gf::MemberShape se = gf::world_member(e, 0.0001, Vector3d::Zero());
  const gf::MemberShape sf = gf::world_member(f, 0.0001, Vector3d(0.0022, 0, 0));
  const gf::MemberContact ef = gf::member_member(se, sf), fe = gf::member_member(sf, se);
  CHECK(ef.delta == Approx(0.0025 - 0.0022 + 0.0002).margin(1e-11));
  CHECK(fe.delta == Approx(ef.delta).margin(1e-11));
  CHECK((ef.n + fe.n).norm() < 1e-6);
}

TEST_CASE("ellipsoid core: a plane's and a drum mantle's overlap follow the support's closed form") {
  const Vector3d axes(0.003, 0.002, 0.001), c(0.0, 0.0021, 0.0);
  const Matrix3d r = turn(0.5, {1, 0.2, 0.4});
  const gf::CorePoints e = ellipsoid(axes, r, c);
  const gf::MemberShape s = gf::world_member(e, 0.0002, c);
  const gf::MemberContact floor = gf::member_plane(s, Vector3d::Zero(), Vector3d::UnitY());
  const double low = -support_height(axes, r, c, -Vector3d::UnitY());  // the core's lowest height
  CHECK(floor.delta == Approx(0.0002 - low).margin(1e-15));
  CHECK(floor.touching() == (0.0002 - low > 0));
  CHECK((floor.n + Vector3d::UnitY()).norm() == 0.0);
  // A drum of radius R about z; the ellipsoid's long axis radial: its farthest point is at x0 + a.
  const double R = 0.05, x0 = 0.047;
  const gf::CorePoints d = ellipsoid(axes, Matrix3d::Identity(), Vector3d(x0, 0, 0));
  const gf::MemberContact m = gf::member_cylinder(gf::world_member(d, 0.0002, Vector3d(x0, 0, 0)), Vector3d::Zero(),
                                                  Vector3d::UnitZ(), R);
  CHECK(m.delta == Approx(x0 + 0.003 + 0.0002 - R).margin(1e-14));
  CHECK((m.n - Vector3d::UnitX()).norm() < 1e-12);
  // Turned, off the axis: the ascent's point against the farthest of 40,000 surface points.
  const Matrix3d t = turn(0.9, {1, 1, 1});
  const Vector3d at(0.03, 0.035, 0.01);
  const gf::CorePoints g = ellipsoid(axes, t, at);
  const gf::MemberContact mg = gf::member_cylinder(gf::world_member(g, 0.0, at), Vector3d::Zero(), Vector3d::UnitZ(), 0.046);
  double farthest = 0;
  for (int i = 0; i <= 200; ++i)
    for (int j = 0; j < 200; ++j) {
      const double th = std::numbers::pi * i / 200, ph = 2 * std::numbers::pi * j / 200;
      const Vector3d p = at + t * Vector3d(axes.x() * std::sin(th) * std::cos(ph), axes.y() * std::sin(th) * std::sin(ph),
                                           axes.z() * std::cos(th));
      farthest = std::max(farthest, p.head<2>().norm());
    }
  // The sampling misses the true maximum by at most a (1 - cos(pi/200)) of the longest semi-axis.
  CHECK(mg.delta + 0.046 >= farthest - 1e-15);
  CHECK(mg.delta + 0.046 <= farthest + 0.003 * (1 - std::cos(std::numbers::pi / 200)) + 1e-15);
}

TEST_CASE("ellipsoid core: mass properties, exact and on the voxel grid") {
  const Vector3d axes(0.003, 0.002, 0.001);
  const gf::MassProperties exact = gf::ellipsoid_mass_properties(axes, 1000.0);
  CHECK(exact.volume == Approx(4.0 / 3.0 * std::numbers::pi * 6e-9).epsilon(1e-14));
  const double m = exact.mass;
  CHECK(exact.moments[0] == Approx(m / 5 * (4e-6 + 1e-6)).epsilon(1e-14));  // about x: b^2 + c^2
  CHECK(exact.moments[2] == Approx(m / 5 * (9e-6 + 4e-6)).epsilon(1e-14));  // about z: a^2 + b^2
  CHECK(exact.axes.determinant() == Approx(1.0));
  // The grid counts the voxels whose centres lie inside: every error comes from the voxels the surface
  // cuts, within (sqrt 3 / 2) h of it on either side, a band of volume at most 2 S (sqrt 3 / 2) h, S below
  // the surface of the box round the ellipsoid; each such voxel moves a moment by at most its mass times
  // the largest squared distance from an axis, (a + h)^2 + (b + h)^2. Loose bounds: the grid does far better.
  const double h = 5e-5, rho = 1000.0;
  const gf::ShapeSpec shape = gf::ellipsoid_shape(axes, 0.0);
  const gf::MassProperties grid = gf::voxel_mass_properties(gf::shape_members(shape), rho, h);
  const double box_surface = 8 * (axes.x() * axes.y() + axes.y() * axes.z() + axes.x() * axes.z());
  const double band = 2 * box_surface * std::sqrt(3.0) / 2 * h;
  CHECK(std::abs(grid.volume - exact.volume) <= band);
  const double arm2 = std::pow(axes.x() + h, 2) + std::pow(axes.y() + h, 2);
  for (int k = 0; k < 3; ++k) CHECK(std::abs(grid.moments[k] - exact.moments[k]) <= rho * band * arm2);
  // The measured agreement, for the record: well within 1 % of the volume.
  CHECK(grid.volume == Approx(exact.volume).epsilon(0.01));
  // Grown by r, the grain's extent along each axis is the one given.
  const gf::ShapeSpec round = gf::ellipsoid_shape(axes, 0.0004);
  const gf::ShapeBox b = gf::core_box(round);
  CHECK(b.hi.x() + 0.0004 == Approx(0.003).epsilon(1e-14));
  CHECK(b.lo.z() - 0.0004 == Approx(-0.001).epsilon(1e-14));
  CHECK_THROWS_WITH(gf::ellipsoid_shape(axes, 0.001), Contains("must exceed the radius"));
}

TEST_CASE("ellipsoid core: a member row bounds itself, and slanted axes are refused") {
  gf::Members members;
  gf::MemberRow row;
  row.kind = static_cast<std::uint8_t>(gf::CoreKind::ellipsoid);
  row.radius = 0.0001;
  row.vertices = {{0.001, 0, 0}, {0.004, 0, 0}, {0.001, 0.002, 0}, {0.001, 0, 0.001}};
  const std::size_t i = members.push(row);
  CHECK(members.bound.cx[i] == 0.001);
  CHECK(members.bound.radius[i] == Approx(0.0031).epsilon(1e-14));
  row.vertices[2] = {0.0015, 0.002, 0};  // the second semi-axis leans on the first
  CHECK_THROWS_WITH(members.push(row), Contains("ellipsoid core") && Contains("not orthogonal"));
  row.vertices.pop_back();
  CHECK_THROWS_WITH(members.push(row), Contains("has 3 points, not 4"));
}
