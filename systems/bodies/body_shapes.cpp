#include "systems/bodies/body_shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <sstream>
#include <string_view>

#include "engine/user_text.hpp"

namespace gf {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

std::string num(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

// ---- Solids as half-spaces, and their cores --------------------------------------------------------

// n . x <= d inside; n a unit vector, outward.
struct Plane {
  Vector3d n;
  double d;
};

void require_length(double v, const char* what) {
  if (!std::isfinite(v) || v <= 0.0)
    throw std::invalid_argument(std::string(what) + " must be positive and finite, not " + num(v));
}

void require_radius(double r) {
  if (!std::isfinite(r) || r < 0.0)
    throw std::invalid_argument("the dilation radius must be finite and not negative, not " + num(r));
}

// The point where three planes meet, when they meet in one point.
std::optional<Vector3d> meet(const Plane& a, const Plane& b, const Plane& c) {
  const Vector3d bc = b.n.cross(c.n);
  const double det = a.n.dot(bc);
  if (std::abs(det) < 1e-12) return std::nullopt;
  return (a.d * bc + b.d * c.n.cross(a.n) + c.d * a.n.cross(b.n)) / det;
}

// The corners of the solid {n . x <= d - r for every plane}: every point where three planes meet
// that no plane excludes, each once. O(planes^4), for the few planes of a builder's solid.
std::vector<Vector3d> corners(const std::vector<Plane>& planes, double tol) {
  std::vector<Vector3d> v;
  for (std::size_t i = 0; i < planes.size(); ++i)
    for (std::size_t j = i + 1; j < planes.size(); ++j)
      for (std::size_t k = j + 1; k < planes.size(); ++k) {
        const std::optional<Vector3d> x = meet(planes[i], planes[j], planes[k]);
        if (!x) continue;
        const bool inside = std::all_of(planes.begin(), planes.end(), [&](const Plane& p) {
          return p.n.dot(*x) <= p.d + tol;
        });
        const bool known = std::any_of(v.begin(), v.end(), [&](const Vector3d& y) { return (y - *x).norm() <= tol; });
        if (inside && !known) v.push_back(*x);
      }
  return v;
}

// The core of a solid given by its face planes: every face moved in by r. Refused when the core has
// no inside (its corners' mean is not strictly inside every plane) or a face no longer reaches the
// core (the dilated part would stop short of that face's plane).
std::vector<Vector3d> core_of(std::vector<Plane> planes, double r, const std::string& what) {
  double scale = 0.0;
  for (const Plane& p : planes) scale = std::max(scale, std::abs(p.d));
  for (Plane& p : planes) p.d -= r;
  const double tol = 1e-9 * scale;
  const std::vector<Vector3d> v = corners(planes, tol);
  const std::string fix = ". Fix: use a dilation radius below half the thinnest width of " + what;
  if (v.size() < 4) throw std::invalid_argument("the dilation radius " + num(r) + " m leaves no core of " + what + fix);
  const Vector3d mean = std::accumulate(v.begin(), v.end(), Vector3d(Vector3d::Zero())) / static_cast<double>(v.size());
  for (const Plane& p : planes) {
    const bool touches = std::any_of(v.begin(), v.end(), [&](const Vector3d& x) { return p.d - p.n.dot(x) <= tol; });
    if (p.d - p.n.dot(mean) <= 1e-6 * scale || !touches)
      throw std::invalid_argument("the dilation radius " + num(r) + " m is too large for " + what + fix);
  }
  if (v.size() > kMaxCoreVertices)
    throw std::invalid_argument(what + " has " + std::to_string(v.size()) + " corners, more than a core may have");
  return v;
}

// A convex polygon's corners counter-clockwise, none straight: every turn strictly to the left. At
// most kMaxCoreVertices / 2 corners, the prism's core having twice as many.
void check_section(std::span<const Vector2d> s) {
  if (s.size() < 3 || s.size() > kMaxCoreVertices / 2)
    throw std::invalid_argument("a prism's section needs 3 to " + std::to_string(kMaxCoreVertices / 2) + " corners, not " +
                                std::to_string(s.size()));
  double size = 0.0;
  for (const Vector2d& p : s) {
    if (!p.allFinite()) throw std::invalid_argument("a prism's section has a corner that is not finite");
    size = std::max(size, p.cwiseAbs().maxCoeff());
  }
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vector2d e0 = s[(i + 1) % s.size()] - s[i], e1 = s[(i + 2) % s.size()] - s[(i + 1) % s.size()];
    if (e0.x() * e1.y() - e0.y() * e1.x() <= 1e-12 * size * size)
      throw std::invalid_argument("a prism's section must be convex, its corners counter-clockwise, none straight");
  }
}

// The planes of a right prism over a convex counter-clockwise section, z in [z0, z1].
std::vector<Plane> prism_planes(std::span<const Vector2d> s, double z0, double z1) {
  std::vector<Plane> planes;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vector2d e = s[(i + 1) % s.size()] - s[i];
    const Vector3d n = Vector3d(e.y(), -e.x(), 0.0).normalized();  // right of the edge: outward
    planes.push_back({n, n.dot(Vector3d(s[i].x(), s[i].y(), 0.0))});
  }
  planes.push_back({Vector3d::UnitZ(), z1});
  planes.push_back({-Vector3d::UnitZ(), -z0});
  return planes;
}

std::vector<Vector3d> prism_core(std::span<const Vector2d> s, double depth, double r, const std::string& what) {
  return core_of(prism_planes(s, -0.5 * depth, 0.5 * depth), r, what);
}

// ---- The up-down cone's parts ---------------------------------------------------------------------

Vector3d ring_corner(double radius, int k, int facets, double z) {
  const double a = 2.0 * std::numbers::pi * k / facets;
  return {radius * std::cos(a), radius * std::sin(a), z};
}

// A regular n-gonal frustum on the z axis: corners on a circle of radius rw at z = zw and of rn at
// z = zn (a single apex when rn is 0). Side planes through three corners, turned outward.
std::vector<Plane> frustum_planes(double rw, double zw, double rn, double zn, int facets) {
  std::vector<Plane> planes;
  for (int k = 0; k < facets; ++k) {
    const Vector3d a = ring_corner(rw, k, facets, zw), b = ring_corner(rw, k + 1, facets, zw);
    const Vector3d c = ring_corner(rn, k, facets, zn);
    Vector3d n = (b - a).cross(c - a).normalized();
    if (n.head<2>().dot(a.head<2>()) < 0.0) n = -n;
    planes.push_back({n, n.dot(a)});
  }
  const double up = zn > zw ? 1.0 : -1.0;
  planes.push_back({-up * Vector3d::UnitZ(), -up * zw});
  if (rn > 0.0) planes.push_back({up * Vector3d::UnitZ(), up * zn});
  return planes;
}

void check_cone(const UpDownCone& c) {
  require_length(c.base_radius, "the cone's base radius");
  require_length(c.height, "the cone's height");
  if (!std::isfinite(c.neck_radius) || c.neck_radius < 0.0 || c.neck_radius >= c.base_radius)
    throw std::invalid_argument("the cone's neck radius must be at least 0 and below the base radius, not " +
                                num(c.neck_radius));
  if (c.facets < 3 || c.facets > static_cast<int>(kMaxCoreVertices / 2))
    throw std::invalid_argument("the cone's facets must be 3 to " + std::to_string(kMaxCoreVertices / 2) + ", not " +
                                std::to_string(c.facets));
  if (c.join == UpDownCone::Join::narrow_ends && c.neck_radius == 0.0)
    throw std::invalid_argument("two pointed cones joined at their tips touch at one point: give a neck radius > 0");
}

// ---- Letters ----------------------------------------------------------------------------------------

using Quad = std::array<Vector2d, 4>;

Quad rect(double x0, double x1, double y0, double y1) { return {{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}; }

// The horizontal width w of a slanted stroke whose width across it is s, over a horizontal extent X
// and a rise dy: w dy = s sqrt((X - w)^2 + dy^2), the root with w > 0.
double slanted_width(double X, double dy, double s) {
  if (dy <= s) throw std::invalid_argument("a slanted stroke must rise more than the stroke width");
  const double w = (s * dy * std::sqrt(X * X + dy * dy - s * s) - s * s * X) / (dy * dy - s * s);
  if (!(w < X)) throw std::invalid_argument("a slanted stroke is wider than the letter: make the stroke narrower");
  return w;
}

// A slanted stroke with horizontal ends: one end on y = y_left, its left corner at x_left; the other
// on y = y_right, its right corner at x_right. Corners counter-clockwise.
Quad slanted(double x_left, double y_left, double x_right, double y_right, double s) {
  const double w = slanted_width(x_right - x_left, std::abs(y_right - y_left), s);
  const Vector2d a(x_left, y_left), b(x_left + w, y_left), c(x_right, y_right), d(x_right - w, y_right);
  if (y_left < y_right) return {a, b, c, d};
  return {d, c, b, a};
}

std::vector<Quad> letter_O(double L, double H, double s) {
  return {rect(-L / 2, -L / 2 + s, -H / 2, H / 2), rect(L / 2 - s, L / 2, -H / 2, H / 2),
          rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-L / 2, L / 2, -H / 2, -H / 2 + s)};
}

std::vector<Quad> letter_T(double L, double H, double s) {
  return {rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-s / 2, s / 2, -H / 2, H / 2)};
}

std::vector<Quad> letter_Z(double L, double H, double s) {
  return {rect(-L / 2, L / 2, H / 2 - s, H / 2), rect(-L / 2, L / 2, -H / 2, -H / 2 + s),
          slanted(-L / 2, -H / 2, L / 2, H / 2, s)};
}

std::vector<Quad> letter_K(double L, double H, double s) {
  return {rect(-L / 2, -L / 2 + s, -H / 2, H / 2), slanted(-L / 2, 0.0, L / 2, H / 2, s),
          slanted(-L / 2, 0.0, L / 2, -H / 2, s)};
}

// The crossbar spans the legs' centre lines at its height, y = -H/4.
std::vector<Quad> letter_A(double L, double H, double s) {
  const Quad left = slanted(-L / 2, -H / 2, s / 2, H / 2, s), right = slanted(-s / 2, H / 2, L / 2, -H / 2, s);
  const double w = left[1].x() - left[0].x(), y = -H / 4;
  const Vector2d bottom(-L / 2 + w / 2, -H / 2), top(s / 2 - w / 2, H / 2);
  const double c = -(bottom.x() + (top.x() - bottom.x()) * (y - bottom.y()) / H);
  return {left, right, rect(-c, c, y - s / 2, y + s / 2)};
}

std::vector<Quad> letter_C(double L, double H, double s) {
  return {rect(-L / 2, -L / 2 + s, -H / 2, H / 2), rect(-L / 2, L / 2, H / 2 - s, H / 2),
          rect(-L / 2, L / 2, -H / 2, -H / 2 + s)};
}

std::vector<Quad> letter_layout(char letter, const LetterSize& z) {
  switch (letter) {
    case 'O': return letter_O(z.width, z.height, z.stroke);
    case 'T': return letter_T(z.width, z.height, z.stroke);
    case 'Z': return letter_Z(z.width, z.height, z.stroke);
    case 'K': return letter_K(z.width, z.height, z.stroke);
    case 'A': return letter_A(z.width, z.height, z.stroke);
    case 'C': return letter_C(z.width, z.height, z.stroke);
    default: break;
  }
  throw std::invalid_argument("no letter shape " + gf::quoted(std::string_view(&letter, 1)) + ": the letters are O, T, Z, K, A, C");
}

void check_letter(const LetterSize& z) {
  require_length(z.width, "the letter's width");
  require_length(z.height, "the letter's height");
  require_length(z.depth, "the letter's depth");
  require_length(z.stroke, "the letter's stroke");
  if (2.0 * z.stroke >= z.width || 3.0 * z.stroke >= z.height)
    throw std::invalid_argument("the letter's stroke " + num(z.stroke) + " m leaves no room between strokes: " +
                                "it must be below half the width and a third of the height");
}

}  // namespace

std::vector<DilatedPolyhedron> shape_members(const ShapeSpec& shape) {
  std::vector<DilatedPolyhedron> members;
  for (std::size_t k = 0; k < shape.parts.size(); ++k) members.push_back({shape.parts[k], shape.radius, shape.kind(k)});
  return members;
}

ShapeBox core_box(const ShapeSpec& shape) {
  ShapeBox b{Vector3d::Constant(std::numeric_limits<double>::infinity()),
             Vector3d::Constant(-std::numeric_limits<double>::infinity())};
  for (std::size_t k = 0; k < shape.parts.size(); ++k) {
    const CorePoints points(shape.parts[k], shape.kind(k));
    for (int a = 0; a < 3; ++a) {
      b.lo[a] = std::min(b.lo[a], core_support(points.view(), -Vector3d::Unit(a))[a]);
      b.hi[a] = std::max(b.hi[a], core_support(points.view(), Vector3d::Unit(a))[a]);
    }
  }
  return b;
}

double shape_reach(const ShapeSpec& shape, const Vector3d& centre) {
  double reach = 0.0;
  for (std::size_t k = 0; k < shape.parts.size(); ++k)
    reach = std::max(reach, core_reach(CorePoints(shape.parts[k], shape.kind(k)).view(), centre));
  return reach + shape.radius;
}

ShapeSpec ellipsoid_shape(const Vector3d& semi_axes, double radius) {
  require_radius(radius);
  for (int a = 0; a < 3; ++a) {
    require_length(semi_axes[a], "an ellipsoid's semi-axis");
    if (!(semi_axes[a] > radius))
      throw std::invalid_argument("an ellipsoid's semi-axes must exceed the radius r, which its core's are reduced by");
  }
  ShapeSpec s{{ellipsoid_core::points(semi_axes - Vector3d::Constant(radius))}, radius};
  s.kinds = {CoreKind::ellipsoid};
  return s;
}

ShapeSpec box_shape(const Vector3d& edges, double radius) {
  for (int a = 0; a < 3; ++a) require_length(edges[a], "a box's edge");
  require_radius(radius);
  const Vector2d h = 0.5 * edges.head<2>();
  const std::array<Vector2d, 4> section{{{-h.x(), -h.y()}, {h.x(), -h.y()}, {h.x(), h.y()}, {-h.x(), h.y()}}};
  return {{prism_core(section, edges.z(), radius, "the box")}, radius};
}

ShapeSpec spheres_shape(std::span<const Vector3d> centres, double radius) {
  require_length(radius, "a sphere's radius");
  if (centres.empty() || centres.size() > kMaxShapeParts)
    throw std::invalid_argument("a shape of spheres needs 1 to " + std::to_string(kMaxShapeParts) + " centres, not " +
                                std::to_string(centres.size()));
  ShapeSpec s{{}, radius};
  for (const Vector3d& c : centres) {
    if (!c.allFinite()) throw std::invalid_argument("a sphere's centre must be finite");
    s.parts.push_back({c});
  }
  return s;
}

ShapeSpec prism_shape(std::span<const Vector2d> section, double length, double radius) {
  check_section(section);
  require_length(length, "a prism's length");
  require_radius(radius);
  return {{prism_core(section, length, radius, "the prism")}, radius};
}

ShapeSpec triangular_prism_shape(double side, double length, double radius) {
  require_length(side, "a triangular prism's side");
  const double R = side / std::sqrt(3.0);  // circumradius
  std::array<Vector2d, 3> section;
  for (int k = 0; k < 3; ++k) {
    const double a = std::numbers::pi / 2 + 2.0 * std::numbers::pi * k / 3;
    section[k] = R * Vector2d(std::cos(a), std::sin(a));
  }
  return prism_shape(section, length, radius);
}

ShapeSpec up_down_cone_shape(const UpDownCone& c, double radius) {
  check_cone(c);
  require_radius(radius);
  const bool narrow = c.join == UpDownCone::Join::narrow_ends;
  const double zw = narrow ? c.height : 0.0, zn = narrow ? 0.0 : c.height;  // the upper part's ends
  ShapeSpec shape{{}, radius};
  for (const double sign : {-1.0, 1.0})
    shape.parts.push_back(
        core_of(frustum_planes(c.base_radius, sign * zw, c.neck_radius, sign * zn, c.facets), radius, "a cone part"));
  return shape;
}

ShapeSpec letter_shape(char letter, const LetterSize& size, double radius) {
  check_letter(size);
  require_radius(radius);
  ShapeSpec shape{{}, radius};
  for (const Quad& q : letter_layout(letter, size))
    shape.parts.push_back(prism_core(q, size.depth, radius, std::string("a stroke of the letter ") + letter));
  return shape;
}

}  // namespace gf
