#include "systems/bodies/member_geometry.hpp"

#include <ccd/ccd.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

// The closest points and depths are doubles throughout; a libccd built for floats would cut them to
// 1e-7 of the grain size.
#ifndef CCD_DOUBLE
#error "libccd must be built with double precision (CCD_DOUBLE)"
#endif

namespace gf {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

Vector3d to_eigen(const ccd_vec3_t& v) { return {v.v[0], v.v[1], v.v[2]}; }
ccd_vec3_t to_ccd(const Vector3d& v) { return {{v.x(), v.y(), v.z()}}; }

// ---- Members in the pair's scaled frame -----------------------------------------------------------

// What libccd's callbacks receive for one member: its core in the pair's frame, where a world point
// p is (p - frame_origin) / scale. The support maps the direction into the member's own frame once
// and scans the vertices there.
struct ScaledCore {
  const MemberShape* shape;
  Matrix3d rotation;  // own frame -> pair frame (the member's rotation over the scale)
  Vector3d offset;    // the own frame's origin in the pair frame
  Vector3d centre;    // the bound's centre in the pair frame: inside the core's hull
};

// The index of the vertex farthest along d (own frame); the first of ties.
std::size_t farthest_vertex(const MemberShape& s, const Vector3d& d) {
  std::size_t best = 0;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s.vertices(); ++i) {
    const double h = s.x[i] * d.x() + s.y[i] * d.y() + s.z[i] * d.z();
    if (h > top) top = h, best = i;
  }
  return best;
}

Vector3d own_vertex(const MemberShape& s, std::size_t i) { return {s.x[i], s.y[i], s.z[i]}; }

// The core's point farthest along d, own frame: a hull's vertex found inline (the contacts' hot
// path), other kinds through their seam (member_core.hpp).
Vector3d own_support(const MemberShape& s, const Vector3d& d) {
  if (s.kind == CoreKind::hull) return own_vertex(s, farthest_vertex(s, d));
  return core_support(s.core(), d);
}

// libccd's support callbacks: the core's point farthest along dir, in the pair frame; a hull's found
// inline, the hot path of every contact between members, any other kind's through its seam.
void ccd_hull_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto& c = *static_cast<const ScaledCore*>(obj);
  const std::size_t i = farthest_vertex(*c.shape, c.shape->rotation.transpose() * to_eigen(*dir));
  *out = to_ccd(c.rotation * own_vertex(*c.shape, i) + c.offset);
}

void ccd_seam_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto& c = *static_cast<const ScaledCore*>(obj);
  *out = to_ccd(c.rotation * core_support(c.shape->core(), c.shape->rotation.transpose() * to_eigen(*dir)) + c.offset);
}

// libccd's centre callback (MPR's interior point).
void scaled_centre(const void* obj, ccd_vec3_t* out) { *out = to_ccd(static_cast<const ScaledCore*>(obj)->centre); }

struct PairFrame {
  Vector3d origin;
  double scale;
};

// About the bounding centres' midpoint, scaled by the sum of the bounding radii (1 if both vanish).
PairFrame pair_frame(const MemberShape& a, const MemberShape& b) {
  const double s = a.bound_radius + b.bound_radius;
  return {0.5 * (a.bound_centre + b.bound_centre), s > 0 ? s : 1.0};
}

ScaledCore scaled_core(const MemberShape& m, const PairFrame& f) {
  return {&m, m.rotation / f.scale, (m.origin - f.origin) / f.scale, (m.bound_centre - f.origin) / f.scale};
}

// The libccd settings for both GJK (here) and MPR: tolerances relative to the pair's size, explicit
// iteration caps. epa_tolerance is set for completeness; EPA is not called.
ccd_t ccd_settings(const MemberShape& a, const MemberShape& b) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = a.kind == CoreKind::hull ? ccd_hull_support : ccd_seam_support;
  ccd.support2 = b.kind == CoreKind::hull ? ccd_hull_support : ccd_seam_support;
  ccd.center1 = ccd.center2 = scaled_centre;
  ccd.max_iterations = kMemberMaxIterations;
  ccd.epa_tolerance = kMemberTolerance;
  ccd.mpr_tolerance = kMemberTolerance;
  ccd.dist_tolerance = kMemberTolerance;
  return ccd;
}

// ---- GJK distance with closest points ---------------------------------------------------------------

// A point of the Minkowski difference A - B and the core points it came from: w = a - b.
struct SupportPoint {
  Vector3d w = Vector3d::Zero(), a = Vector3d::Zero(), b = Vector3d::Zero();
};

SupportPoint support(const void* a, const void* b, const ccd_t& ccd, const Vector3d& dir) {
  const ccd_vec3_t d = to_ccd(dir), nd = to_ccd(-dir);
  ccd_vec3_t pa, pb;
  ccd.support1(a, &d, &pa);
  ccd.support2(b, &nd, &pb);
  const Vector3d va = to_eigen(pa), vb = to_eigen(pb);
  return {va - vb, va, vb};
}

// A simplex with the barycentric weights of its point closest to the origin.
struct Simplex {
  std::array<SupportPoint, 4> p;
  std::array<double, 4> weight{};
  int size = 0;

  Vector3d closest() const {
    Vector3d v = Vector3d::Zero();
    for (int i = 0; i < size; ++i) v += weight[i] * p[i].w;
    return v;
  }
};

Simplex vertex_simplex(const SupportPoint& a) {
  Simplex s;
  s.p[0] = a, s.weight[0] = 1.0, s.size = 1;
  return s;
}

Simplex two(const SupportPoint& a, const SupportPoint& b, double wa, double wb) {
  Simplex s;
  s.p[0] = a, s.p[1] = b, s.weight = {wa, wb, 0, 0}, s.size = 2;
  return s;
}

// The closest point of segment ab to the origin, reduced to the vertex or the segment holding it.
Simplex closest_segment(const SupportPoint& a, const SupportPoint& b) {
  const Vector3d ab = b.w - a.w;
  const double t = -a.w.dot(ab), len2 = ab.squaredNorm();
  if (t <= 0.0) return vertex_simplex(a);
  if (t >= len2) return vertex_simplex(b);
  return two(a, b, 1.0 - t / len2, t / len2);
}

// Of several candidate sub-simplices, the one whose point is nearest the origin.
template <std::size_t N>
Simplex nearest_of(const std::array<Simplex, N>& c) {
  return *std::min_element(c.begin(), c.end(), [](const Simplex& x, const Simplex& y) {
    return x.closest().squaredNorm() < y.closest().squaredNorm();
  });
}

// The closest point of triangle abc to the origin by its Voronoi regions (Ericson 2005, 5.1.5). A
// degenerate (collinear) triangle has no face region: the nearest of its edges then.
Simplex closest_triangle(const SupportPoint& a, const SupportPoint& b, const SupportPoint& c) {
  const Vector3d ab = b.w - a.w, ac = c.w - a.w;
  const double d1 = -ab.dot(a.w), d2 = -ac.dot(a.w);
  if (d1 <= 0 && d2 <= 0) return vertex_simplex(a);
  const double d3 = -ab.dot(b.w), d4 = -ac.dot(b.w);
  if (d3 >= 0 && d4 <= d3) return vertex_simplex(b);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return two(a, b, 1.0 - d1 / (d1 - d3), d1 / (d1 - d3));
  const double d5 = -ab.dot(c.w), d6 = -ac.dot(c.w);
  if (d6 >= 0 && d5 <= d6) return vertex_simplex(c);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return two(a, c, 1.0 - d2 / (d2 - d6), d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return two(b, c, 1.0 - t, t);
  }
  const double sum = va + vb + vc;
  if (!(sum > 0)) return nearest_of<3>({closest_segment(a, b), closest_segment(a, c), closest_segment(b, c)});
  Simplex s;
  s.p[0] = a, s.p[1] = b, s.p[2] = c;
  s.weight = {va / sum, vb / sum, vc / sum, 0.0};
  s.size = 3;
  return s;
}

// The origin's side of plane (p, q, r) against the side of `opposite`: true when the origin lies
// strictly beyond the face (or the tetrahedron is flat there, so the face must be checked too).
bool origin_beyond(const Vector3d& p, const Vector3d& q, const Vector3d& r, const Vector3d& opposite) {
  const Vector3d n = (q - p).cross(r - p);
  const double s_origin = -n.dot(p), s_opposite = n.dot(opposite - p);
  const double flat = std::numeric_limits<double>::epsilon() * n.norm() * (opposite - p).norm();
  return std::abs(s_opposite) <= flat || s_origin * s_opposite < 0;
}

// The closest point of tetrahedron abcd to the origin: the nearest of the faces the origin lies
// beyond; size 4 (the whole tetrahedron) when it lies beyond none, that is inside.
Simplex closest_tetrahedron(const Simplex& t) {
  const SupportPoint &a = t.p[0], &b = t.p[1], &c = t.p[2], &d = t.p[3];
  const std::array<std::array<const SupportPoint*, 4>, 4> faces{
      {{&a, &b, &c, &d}, {&a, &c, &d, &b}, {&a, &d, &b, &c}, {&b, &d, &c, &a}}};
  Simplex best = t;
  double best_d2 = std::numeric_limits<double>::infinity();
  for (const auto& f : faces) {
    if (!origin_beyond(f[0]->w, f[1]->w, f[2]->w, f[3]->w)) continue;
    const Simplex s = closest_triangle(*f[0], *f[1], *f[2]);
    const double d2 = s.closest().squaredNorm();
    if (d2 < best_d2) best = s, best_d2 = d2;
  }
  return best;
}

Simplex reduce(const Simplex& s) {
  switch (s.size) {
    case 2: return closest_segment(s.p[0], s.p[1]);
    case 3: return closest_triangle(s.p[0], s.p[1], s.p[2]);
    case 4: return closest_tetrahedron(s);
    default: return s;
  }
}

struct GjkResult {
  bool overlap = false;  // the cores intersect or touch within the tolerance
  Vector3d v;            // the closest point of A - B to the origin (pair frame)
  Vector3d pa, pb;       // the cores' closest points (pair frame)
  int size = 0;          // of the final simplex: 3 when v lies inside a face of A - B
};

GjkResult gjk_result(const Simplex& s, bool overlap) {
  GjkResult r{overlap, s.closest(), Vector3d::Zero(), Vector3d::Zero(), s.size};
  for (int i = 0; i < s.size; ++i) r.pa += s.weight[i] * s.p[i].a, r.pb += s.weight[i] * s.p[i].b;
  return r;
}

// GJK distance (van den Bergen 1999): the simplex's closest point v approaches the origin through
// support points along -v; d lies in [v.w / |v|, |v|], and the loop stops when that interval is
// within the tolerance, when v stops shrinking (round-off), or when the origin is inside.
GjkResult gjk_distance(const void* a, const void* b, const ccd_t& ccd) {
  ccd_vec3_t ca, cb;
  ccd.center1(a, &ca);
  ccd.center2(b, &cb);
  Vector3d v = to_eigen(ca) - to_eigen(cb);
  if (v.squaredNorm() == 0) v = Vector3d::UnitX();
  Simplex s = vertex_simplex(support(a, b, ccd, -v));
  const double tol = ccd.dist_tolerance;
  for (unsigned long it = 0; it < ccd.max_iterations; ++it) {
    v = s.closest();
    const double v2 = v.squaredNorm();
    if (v2 <= tol * tol) return gjk_result(s, true);
    const SupportPoint w = support(a, b, ccd, -v);
    if (v2 - v.dot(w.w) <= tol * std::sqrt(v2)) break;
    Simplex next = s;
    next.p[next.size++] = w;
    next = reduce(next);
    if (next.size == 4) return gjk_result(s, true);
    if (next.closest().squaredNorm() >= v2) break;
    s = next;
  }
  return gjk_result(s, false);
}

// ---- Contacts ----------------------------------------------------------------------------------------

// The fields that follow from the normal, the cores' distance and the midpoint of their closest
// points (world); the contact point is that moved by (r_A - r_B)/2 along n.
MemberContact finish(MemberProximity kind, const Vector3d& n, double core_distance, const Vector3d& between,
                     double ra, double rb, const Vector3d& com_a, const Vector3d& com_b) {
  MemberContact c;
  c.kind = kind;
  c.n = n;
  c.core_distance = core_distance;
  c.delta = ra + rb - core_distance;
  c.point = between + 0.5 * (ra - rb) * n;
  c.arm_a = c.point - com_a;
  c.arm_b = c.point - com_b;
  return c;
}

MemberContact apart(const MemberShape& a, const MemberShape& b, double centres) {
  MemberContact c;
  c.delta = a.bound_radius + b.bound_radius - centres;
  return c;
}

// ---- Penetrating cores -------------------------------------------------------------------------------

// libccd's MPR direction (the outward normal of A - B where the ray from the cores' centres leaves
// it: the way B must move to come free); the bounding centres' direction when MPR finds the cores
// only touching (no depth, no direction) or apart within round-off.
Vector3d mpr_direction(const ScaledCore& sa, const ScaledCore& sb, const ccd_t& ccd) {
  ccd_real_t depth = 0;
  ccd_vec3_t dir, pos;
  if (ccdMPRPenetration(&sa, &sb, &ccd, &depth, &dir, &pos) == 0) {
    const Vector3d n = to_eigen(dir);
    if (depth > 0 && n.allFinite() && std::abs(n.norm() - 1.0) < 1e-6) return n.normalized();
  }
  const Vector3d c = sb.centre - sa.centre;
  return c.norm() > 0 ? c.normalized() : Vector3d::UnitZ();
}

// B's core moved by t (pair frame).
ScaledCore shifted(ScaledCore c, const Vector3d& t) {
  c.offset += t, c.centre += t;
  return c;
}

struct Penetration {
  Vector3d n;       // outward normal of A - B: from A to B
  double depth;     // the support of A - B along n: the penetration along n (< 0 if apart)
  Vector3d pa, pb;  // the cores' points farthest into each other along n (pair frame)
  bool on_face;     // the support point lies inside a face of A - B (not on an edge or a vertex)
};

// One descent step from direction u: the point q a margin beyond A - B along u lies outside it, so
// GJK finds its closest point c on A - B; the outward normal there, n = (q - c)/|q - c|, has c as its
// support point, so the depth along n is c . n, which is at most the depth along u (|q - c| is at
// least the margin). c and the cores' points come from GJK's closest points with B moved back.
Penetration descend(const ScaledCore& sa, const ScaledCore& sb, const ccd_t& ccd, const Vector3d& u) {
  constexpr double kMargin = 0.05;  // of the pair's size: normals from GJK at that gap are exact to 1e-14
  const Vector3d q = (support(&sa, &sb, ccd, u).w.dot(u) + kMargin) * u;
  const ScaledCore moved = shifted(sb, q);
  const GjkResult g = gjk_distance(&sa, &moved, ccd);
  const Vector3d n = -g.v.normalized(), pb = g.pb - q;
  return {n, (g.pa - pb).dot(n), g.pa, pb, g.size == 3};
}

// Descends from p until the normal stops turning (kTurn radians: GJK's normals at the margin's gap
// are exact to 1e-14).
Penetration settle(const ScaledCore& sa, const ScaledCore& sb, const ccd_t& ccd, Penetration p) {
  constexpr double kTurn = 1e-10;
  for (unsigned long it = 0; it < ccd.max_iterations; ++it) {
    const Penetration next = descend(sa, sb, ccd, p.n);
    if (next.depth > p.depth + ccd.dist_tolerance) return p;  // round-off turned it back
    const bool still = (next.n - p.n).norm() <= kTurn;
    p = next;
    if (still) return p;
  }
  return p;
}

// From a stop on an edge or a vertex of A - B, where the depth is a maximum across the stop (its
// normal cone): the direction tilted by 0.1 rad four ways, each descended, the shallowest kept. A
// flat A - B (a plate's or a segment's core against a point or a parallel core; crossed segments)
// has no faces to stop on and needs this: its depth is 0 along its plane's normal.
Penetration leave_edge(const ScaledCore& sa, const ScaledCore& sb, const ccd_t& ccd, const Penetration& p) {
  constexpr double kTilt = 0.1;
  const Vector3d t1 = p.n.unitOrthogonal(), t2 = p.n.cross(t1);
  Penetration best = p;
  for (const Vector3d& t : std::array<Vector3d, 4>{t1, -t1, t2, -t2}) {
    const Vector3d u = (std::cos(kTilt) * p.n + std::sin(kTilt) * t).normalized();
    const Penetration q = settle(sa, sb, ccd, descend(sa, sb, ccd, u));
    if (q.depth < best.depth - ccd.dist_tolerance) best = q;
  }
  return best;
}

// The penetration from MPR's direction, made exact: descend until the normal stops turning. That is
// a face of A - B holding the origin's foot on its plane, a local minimum of the penetration depth
// (the face MPR's ray leaves by, when that holds the foot; leave_edge's when the descent stopped
// off a face), and the last step, taken along the face's normal, puts the cores' points on the
// foot: p_A - p_B = depth n. MPR's own depth, the distance to its last portal triangle, depends on
// the path its portal took (which member comes first, round-off in the ties of the support), by up
// to 54 um on millimetre grains; the face's does not.
// A smooth core (not a hull) makes A - B smooth: no edge to leave, the descent's stop is the minimum.
Penetration penetration(const ScaledCore& sa, const ScaledCore& sb, const ccd_t& ccd) {
  const Penetration p = settle(sa, sb, ccd, descend(sa, sb, ccd, mpr_direction(sa, sb, ccd)));
  const bool smooth = sa.shape->kind != CoreKind::hull || sb.shape->kind != CoreKind::hull;
  return p.on_face || smooth ? p : leave_edge(sa, sb, ccd, p);
}

Vector3d mean_of(const MemberShape& m, auto&& keep) {
  Vector3d sum = Vector3d::Zero();
  double count = 0;
  for (std::size_t i = 0; i < m.vertices(); ++i)
    if (keep(i)) sum += own_vertex(m, i), count += 1;
  return sum / count;
}

// Mean of the vertices i with height base + d.v_i below r, each weighted by r minus its height.
Vector3d depth_weighted(const MemberShape& m, const Vector3d& d, double base, double r) {
  Vector3d sum = Vector3d::Zero();
  double weight = 0;
  for (std::size_t i = 0; i < m.vertices(); ++i) {
    const double w = r - (base + d.dot(own_vertex(m, i)));
    if (w > 0) sum += w * own_vertex(m, i), weight += w;
  }
  return sum / weight;
}

MemberShape with_bound(MemberShape s) {
  const Vector3d c = core_centre(s.core());
  s.bound_centre = s.origin + s.rotation * c;
  s.bound_radius = core_reach(s.core(), c) + s.radius;
  return s;
}

MemberShape shape_of(const CorePoints& core, double radius, const Vector3d& origin, const Matrix3d& rotation,
                     const Vector3d& com) {
  check_core(core.view());
  MemberShape s;
  s.kind = core.kind;
  s.x = core.x, s.y = core.y, s.z = core.z;
  s.rotation = rotation, s.origin = origin, s.radius = radius, s.centre_of_mass = com;
  return with_bound(s);
}

}  // namespace

Vector3d MemberShape::vertex(std::size_t i) const { return origin + rotation * own_vertex(*this, i); }

Vector3d MemberShape::support(const Vector3d& d) const {
  return origin + rotation * own_support(*this, rotation.transpose() * d);
}

MemberShape member_shape(const Bodies& bodies, const Members& members, std::size_t m) {
  const std::uint32_t b = members.body.row[m], first = members.core.first[m], count = members.core.count[m];
  MemberShape s;
  s.kind = static_cast<CoreKind>(members.core.kind[m]);
  s.x = std::span<const double>(members.vertices.x.data() + first, count);
  s.y = std::span<const double>(members.vertices.y.data() + first, count);
  s.z = std::span<const double>(members.vertices.z.data() + first, count);
  s.rotation = Eigen::Quaterniond(bodies.q.w[b], bodies.q.x[b], bodies.q.y[b], bodies.q.z[b]).toRotationMatrix();
  s.origin = s.centre_of_mass = Vector3d(bodies.pos.x[b], bodies.pos.y[b], bodies.pos.z[b]);
  s.radius = members.dilation.r[m];
  s.bound_centre = s.origin + s.rotation * Vector3d(members.bound.cx[m], members.bound.cy[m], members.bound.cz[m]);
  s.bound_radius = members.bound.radius[m];
  return s;
}

MemberShape posed_member(const CorePoints& core, double radius, const Vector3d& origin, const Matrix3d& rotation) {
  return shape_of(core, radius, origin, rotation, origin);
}

MemberShape world_member(const CorePoints& core, double radius, const Vector3d& centre_of_mass) {
  return shape_of(core, radius, Vector3d::Zero(), Matrix3d::Identity(), centre_of_mass);
}

MemberContact member_member(const MemberShape& a, const MemberShape& b) {
  const double centres = (b.bound_centre - a.bound_centre).norm();
  if (centres >= a.bound_radius + b.bound_radius) return apart(a, b, centres);
  const PairFrame f = pair_frame(a, b);
  const ScaledCore sa = scaled_core(a, f), sb = scaled_core(b, f);
  const ccd_t ccd = ccd_settings(a, b);
  const GjkResult g = gjk_distance(&sa, &sb, ccd);
  if (!g.overlap) {
    const double d = g.v.norm();
    const Vector3d mid = f.origin + 0.5 * f.scale * (g.pa + g.pb);
    return finish(MemberProximity::separated, -g.v / d, f.scale * d, mid, a.radius, b.radius, a.centre_of_mass,
                  b.centre_of_mass);
  }
  const Penetration p = penetration(sa, sb, ccd);
  const Vector3d mid = f.origin + 0.5 * f.scale * (p.pa + p.pb);
  return finish(p.depth > 0 ? MemberProximity::penetrating : MemberProximity::separated, p.n, -f.scale * p.depth, mid,
                a.radius, b.radius, a.centre_of_mass, b.centre_of_mass);
}

MemberContact member_sphere(const MemberShape& a, const Vector3d& centre, double radius) {
  static constexpr double kOrigin[1] = {0.0};
  MemberShape s;
  s.x = s.y = s.z = std::span<const double>(kOrigin, 1);
  s.origin = s.centre_of_mass = s.bound_centre = centre;
  s.radius = s.bound_radius = radius;
  return member_member(a, s);
}

namespace {

// A smooth core meets a plane at its one lowest point (own-frame normal d, the frame origin's height base).
MemberContact smooth_plane(const MemberShape& a, const Vector3d& d, double base, const Vector3d& normal) {
  const Vector3d low = own_support(a, -d);
  const double h = base + d.dot(low);
  const Vector3d lowest = a.origin + a.rotation * low;
  MemberContact c = finish(h < 0 ? MemberProximity::penetrating : MemberProximity::separated, -normal, h,
                           lowest - 0.5 * h * normal, a.radius, 0.0, a.centre_of_mass, Vector3d::Zero());
  c.arm_b = Vector3d::Zero();
  return c;
}

// A smooth core's point farthest from the cylinder's axis, by ascent on support points: from the
// radial direction u at point x, the support point along u is at least as far from the axis (its
// radial component along u is at least x's). Ends when a step gains less than 1e-12 of the bound.
Vector3d farthest_from_axis(const MemberShape& a, const Vector3d& point, const Vector3d& axis) {
  const auto radial = [&](const Vector3d& x) {
    const Vector3d d = x - point;
    return Vector3d(d - d.dot(axis) * axis);
  };
  Vector3d out = radial(a.bound_centre);
  if (!(out.norm() > 0)) out = axis.unitOrthogonal();
  Vector3d x = a.support(out.normalized());
  double rho = radial(x).norm();
  for (unsigned long it = 0; it < kMemberMaxIterations; ++it) {
    const Vector3d u = radial(x);
    if (!(u.norm() > 0)) break;
    const Vector3d next = a.support(u / u.norm());
    const double r = radial(next).norm();
    if (r <= rho + kMemberTolerance * a.bound_radius) {
      if (r > rho) x = next;
      break;
    }
    x = next, rho = r;
  }
  return x;
}

MemberContact smooth_cylinder(const MemberShape& a, const Vector3d& point, const Vector3d& axis, double radius) {
  const Vector3d x = farthest_from_axis(a, point, axis);
  const Vector3d d = x - point, out = d - d.dot(axis) * axis;
  const double rho = out.norm(), depth = rho + a.radius - radius;
  MemberContact c;
  c.kind = rho > radius ? MemberProximity::penetrating : MemberProximity::separated;
  c.delta = depth;
  c.core_distance = a.radius - depth;
  if (!(depth > 0) || !(rho > 0)) return c;
  c.n = out / rho;
  c.point = x + (a.radius - 0.5 * depth) * c.n;
  c.arm_a = c.point - a.centre_of_mass;
  c.arm_b = Vector3d::Zero();
  return c;
}

}  // namespace

MemberContact member_plane(const MemberShape& a, const Vector3d& point, const Vector3d& normal) {
  const double bound_height = normal.dot(a.bound_centre - point);
  if (bound_height >= a.bound_radius) {
    MemberContact c;
    c.delta = a.bound_radius - bound_height;
    return c;
  }
  const Vector3d d = a.rotation.transpose() * normal;
  const double base = normal.dot(a.origin - point);
  if (a.kind != CoreKind::hull) return smooth_plane(a, d, base, normal);
  const double low = d.dot(own_vertex(a, farthest_vertex(a, -d)));
  const double tie = kMemberTolerance * a.bound_radius;
  const auto tied = [&](std::size_t i) { return d.dot(own_vertex(a, i)) <= low + tie; };
  const double h = base + low;
  // Where the force acts: the vertices whose dilation spheres reach through the plane, weighted by
  // how far (r - their height). A face resting nearly flat then pushes at its middle, and a tilt
  // moves the point towards the deeper side, a torque that grows with the tilt; the lowest vertex
  // alone would flip the torque's sign from corner to corner at every step's round-off.
  const Vector3d lowest = a.origin + a.rotation * (h < a.radius ? depth_weighted(a, d, base, a.radius) : mean_of(a, tied));
  // Between the core (lowest) and the plane (lowest - h normal); finish moves it by r/2 along -normal,
  // to midway between the member's surface and the plane.
  MemberContact c = finish(h < 0 ? MemberProximity::penetrating : MemberProximity::separated, -normal, h,
                           lowest - 0.5 * h * normal, a.radius, 0.0, a.centre_of_mass, Vector3d::Zero());
  c.arm_b = Vector3d::Zero();
  return c;
}

MemberContact member_cylinder(const MemberShape& a, const Vector3d& point, const Vector3d& axis, double radius) {
  const auto radial = [&](const Vector3d& x) {
    const Vector3d d = x - point;
    return Vector3d(d - d.dot(axis) * axis);
  };
  const double centre = radial(a.bound_centre).norm();
  if (centre + a.bound_radius <= radius) {
    MemberContact c;
    c.delta = centre + a.bound_radius - radius;
    return c;
  }
  if (a.kind != CoreKind::hull) return smooth_cylinder(a, point, axis, radius);
  double deepest = -std::numeric_limits<double>::infinity(), farthest = 0, weight = 0;
  Vector3d at = Vector3d::Zero(), dir = Vector3d::Zero();
  for (std::size_t i = 0; i < a.vertices(); ++i) {
    const Vector3d x = a.vertex(i), out = radial(x);
    const double rho = out.norm(), depth = rho + a.radius - radius;
    deepest = std::max(deepest, depth);
    farthest = std::max(farthest, rho);
    if (depth <= 0 || rho <= 0) continue;
    const Vector3d u = out / rho;
    at += depth * (x + (a.radius - 0.5 * depth) * u);
    dir += depth * u;
    weight += depth;
  }
  MemberContact c;
  c.kind = farthest > radius ? MemberProximity::penetrating : MemberProximity::separated;
  c.delta = deepest;
  c.core_distance = a.radius - deepest;
  if (!(deepest > 0) || !(dir.norm() > 0)) return c;
  c.n = dir.normalized();
  c.point = at / weight;
  c.arm_a = c.point - a.centre_of_mass;
  c.arm_b = Vector3d::Zero();
  return c;
}

ContactGeometry<double> contact_geometry(const MemberContact& c, const Vector3d& v_a, const Vector3d& w_a,
                                         const Vector3d& v_b, const Vector3d& w_b) {
  const Vector3d v = v_a + w_a.cross(c.arm_a) - v_b - w_b.cross(c.arm_b);
  const Vector3d w = w_a - w_b;
  ContactGeometry<double> g;
  g.n = {c.n.x(), c.n.y(), c.n.z()};
  g.delta = c.delta;
  g.v = {v.x(), v.y(), v.z()};
  g.w = {w.x(), w.y(), w.z()};
  return g;
}

}  // namespace gf
