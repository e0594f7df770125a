// The shape library of composite grains (systems/bodies/body_shapes.hpp): each primitive's and each
// letter's volume and centre from the background-grid mass properties against closed forms, the
// cores' inset by the dilation radius, and the letters' holes and notches (the OBJ and STL readers:
// shape_files_test.cpp).
//
// Tolerances from the voxel edge h, as in mass_properties_test.cpp. Let C be the voxel cube and B(s)
// the ball of radius s = sqrt(3) h / 2 that holds it. The counted voxels lie between K - C and K + C
// (K the union of the dilated parts P_i), and for a union both differences are bounded part by part:
// (K + C) \ K lies in the union of (P_i + C) \ P_i and K \ (K - C) in that of P_i \ (P_i - C), each of
// volume at most V(P_i + B(s)) - V(P_i) = S s + M s^2 + 4/3 pi s^3 (Steiner; S the part's surface
// area, M its integral of mean curvature, sum over edges of length times external angle / 2). So
// |V_voxels - V| <= sum_i [V(P_i + B(s)) - V(P_i)] =: E, and the centre moves by at most 2 E times the
// largest distance from the centre to K + B(s), over the counted volume. A part P_i = core_i + B(r)
// has V(P_i + B(s)) = W(core_i, r + s), W the core's Steiner polynomial.
#include "systems/bodies/body_shapes.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <vector>

using Eigen::Vector2d;
using Eigen::Vector3d;
using gf::ShapeSpec;

namespace {

constexpr double kPi = std::numbers::pi;

// A convex body's Steiner polynomial: V(K + B(t)) = V + S t + M t^2 + 4/3 pi t^3.
struct Quermass {
  double V = 0, S = 0, M = 0;
  double at(double t) const { return V + S * t + M * t * t + 4.0 / 3.0 * kPi * t * t * t; }
};

// A box of edges a, b, c (Steiner's formula for a box).
Quermass box_q(const Vector3d& L) {
  return {L.prod(), 2.0 * (L.x() * L.y() + L.y() * L.z() + L.z() * L.x()), kPi * L.sum()};
}

// A right prism over a convex section of area A and perimeter p, of length l: its lateral edges turn
// by 2 pi in all (pi l), its cap edges by pi/2 each (pi p / 2).
Quermass prism_q(double A, double p, double l) { return {A * l, 2.0 * A + p * l, kPi * (l + 0.5 * p)}; }

// A regular n-gonal frustum: corners on circles of radius R1 (wide end, z = 0) and R2 (z = h).
struct Frustum {
  int n;
  double R1, R2, h;
  double apothem(double R) const { return R * std::cos(kPi / n); }
  double area(double R) const { return 0.5 * n * R * R * std::sin(2.0 * kPi / n); }
  double slant() const { return std::hypot(h, apothem(R1) - apothem(R2)); }
  double volume() const { return h / 3.0 * (area(R1) + area(R2) + std::sqrt(area(R1) * area(R2))); }
  // The centroid's height above the wide end.
  double centroid() const {
    const double a = area(R1), b = area(R2), m = std::sqrt(a * b);
    return h * (a + 2.0 * m + 3.0 * b) / (4.0 * (a + m + b));
  }
  Quermass quermass() const {
    const double e1 = 2.0 * R1 * std::sin(kPi / n), e2 = 2.0 * R2 * std::sin(kPi / n);
    const double da = apothem(R1) - apothem(R2), hs = slant();
    const double lateral = std::hypot(h, R1 - R2);
    // External angles: side face against the wide cap, the narrow cap, and the next side face.
    const double at_wide = std::acos(-da / hs), at_narrow = std::acos(da / hs);
    const double at_side = std::acos((h * h * std::cos(2.0 * kPi / n) + da * da) / (hs * hs));
    const double S = area(R1) + area(R2) + n * 0.5 * (e1 + e2) * hs;
    const double M = 0.5 * n * (e1 * at_wide + e2 * at_narrow + lateral * at_side);
    return {volume(), S, M};
  }
  // Every face moved in by r: the side planes' apothem at each height shrinks by r hs / h.
  Frustum inset(double r) const {
    const double shrink = r * slant() / h, c = std::cos(kPi / n);
    auto a_at = [&](double z) { return apothem(R1) + (apothem(R2) - apothem(R1)) * z / h; };
    return {n, (a_at(r) - shrink) / c, (a_at(h - r) - shrink) / c, h - 2.0 * r};
  }
};

// The largest distance from c to the parts' vertices.
double reach(const ShapeSpec& s, const Vector3d& c) {
  double d = 0;
  for (const auto& part : s.parts)
    for (const Vector3d& x : part) d = std::max(d, (x - c).norm());
  return d;
}

gf::MassProperties props(const ShapeSpec& s, double h) { return gf::voxel_mass_properties(gf::shape_members(s), 1.0, h); }

double grid_s(double h) { return std::sqrt(3.0) / 2.0 * h; }

// ---- Supporting planes and the inset --------------------------------------------------------------

struct Plane {
  Vector3d n;
  double d;
};

// The planes through three vertices that leave every vertex on one side, turned outward.
std::vector<Plane> support_planes(const std::vector<Vector3d>& v) {
  std::vector<Plane> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      for (std::size_t k = j + 1; k < v.size(); ++k) {
        const Vector3d n = (v[j] - v[i]).cross(v[k] - v[i]);
        if (n.norm() < 1e-12) continue;
        const Vector3d u = n.normalized();
        double lo = 0, hi = 0;
        for (const Vector3d& x : v) lo = std::min(lo, u.dot(x - v[i])), hi = std::max(hi, u.dot(x - v[i]));
        if (lo < -1e-12 && hi > 1e-12) continue;
        out.push_back(hi > 1e-12 ? Plane{-u, -u.dot(v[i])} : Plane{u, u.dot(v[i])});
      }
  return out;
}

// The core lies r inside every face plane of the solid and touches each moved plane: the dilated
// part is the solid with rounded convex edges. Returns the largest deviation found.
double inset_error(const std::vector<Vector3d>& solid, const std::vector<Vector3d>& core, double r) {
  double worst = 0;
  for (const Plane& p : support_planes(solid)) {
    double closest = 1e300;
    for (const Vector3d& x : core) closest = std::min(closest, p.d - p.n.dot(x));
    worst = std::max(worst, std::abs(closest - r));
  }
  return worst;
}

// ---- Sections of letters ------------------------------------------------------------------------------

using Polygon = std::vector<Vector2d>;

double cross2(const Vector2d& a, const Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// A part's section: its vertices on the top face, counter-clockwise about their mean.
Polygon section(const std::vector<Vector3d>& part) {
  double top = -1e300;
  for (const Vector3d& x : part) top = std::max(top, x.z());
  Polygon p;
  for (const Vector3d& x : part)
    if (x.z() > top - 1e-12) p.emplace_back(x.x(), x.y());
  Vector2d c = Vector2d::Zero();
  for (const Vector2d& x : p) c += x / static_cast<double>(p.size());
  std::sort(p.begin(), p.end(), [&](const Vector2d& a, const Vector2d& b) {
    return std::atan2(a.y() - c.y(), a.x() - c.x()) < std::atan2(b.y() - c.y(), b.x() - c.x());
  });
  return p;
}

// Sutherland-Hodgman: the part of `p` on the left of every edge of the convex counter-clockwise `clip`.
Polygon clip(const Polygon& p, const Polygon& by) {
  Polygon out = p;
  for (std::size_t e = 0; e < by.size() && !out.empty(); ++e) {
    const Vector2d a = by[e], b = by[(e + 1) % by.size()];
    auto side = [&](const Vector2d& x) { return cross2(b - a, x - a); };
    Polygon next;
    for (std::size_t i = 0; i < out.size(); ++i) {
      const Vector2d x = out[i], y = out[(i + 1) % out.size()];
      const double sx = side(x), sy = side(y);
      if (sx >= 0) next.push_back(x);
      if ((sx >= 0) != (sy >= 0)) next.push_back(x + (y - x) * (sx / (sx - sy)));
    }
    out = next;
  }
  return out;
}

struct AreaMoment {
  double area = 0;
  Vector2d first = Vector2d::Zero();  // integral of x over the polygon
};

AreaMoment moments(const Polygon& p) {
  AreaMoment m;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector2d a = p[i], b = p[(i + 1) % p.size()];
    const double w = cross2(a, b);
    m.area += 0.5 * w;
    m.first += (a + b) * w / 6.0;
  }
  return m;
}

// The union's area and first moment by inclusion and exclusion over every set of sections.
AreaMoment union_moments(const std::vector<Polygon>& parts) {
  AreaMoment total;
  for (unsigned mask = 1; mask < (1u << parts.size()); ++mask) {
    Polygon common;
    bool first = true;
    for (std::size_t i = 0; i < parts.size(); ++i)
      if (mask >> i & 1) common = first ? parts[i] : clip(common, parts[i]), first = false;
    const AreaMoment m = moments(common);
    const double sign = std::popcount(mask) % 2 ? 1.0 : -1.0;
    total.area += sign * m.area, total.first += sign * m.first;
  }
  return total;
}

double perimeter(const Polygon& p) {
  double L = 0;
  for (std::size_t i = 0; i < p.size(); ++i) L += (p[(i + 1) % p.size()] - p[i]).norm();
  return L;
}

// The polygon's width: the least over its edges of the farthest corner from the edge's line.
double width(const Polygon& p) {
  double w = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Vector2d a = p[i], e = (p[(i + 1) % p.size()] - a).normalized();
    double far = 0;
    for (const Vector2d& x : p) far = std::max(far, std::abs(cross2(e, x - a)));
    w = std::min(w, far);
  }
  return w;
}

// Outside every member: the distance from p to each core exceeds r.
double clearance(const ShapeSpec& s, const Vector3d& p) {
  double d = 1e300;
  for (const auto& part : s.parts) d = std::min(d, gf::ConvexCore(part).distance(p) - s.radius);
  return d;
}

}  // namespace

// ---- Primitives ---------------------------------------------------------------------------------------

TEST_CASE("body_shapes: a box's volume and centre, sharp and dilated (Steiner)", "[bodies]") {
  // Sharp: the box is centred on the grid, so the counted voxels form a box of edges in [L, L + h)
  // and the centre is exact to round-off. Dilated: outer edges E, core edges E - 2r, volume
  // W(E - 2r, r); the core is aligned with the grid, so the counted voxels lie between the core
  // grown and shrunk by h/2, each dilated by r. Measured volume errors (h = 1.3 mm): sharp 6.7e-2
  // of V (bound 0.10), dilated 3.9e-2 (bound 0.10); both centres 0 (bound 1e-12 of the size).
  const Vector3d E(0.04, 0.03, 0.06);
  const double h = 0.0013;  // no edge a whole number of voxels
  const ShapeSpec sharp = gf::box_shape(E, 0.0);
  REQUIRE(sharp.parts.size() == 1);
  REQUIRE(sharp.parts[0].size() == 8);
  const gf::MassProperties p = props(sharp, h);
  const double V = E.prod();
  CHECK(std::abs(p.volume - V) <= (E + Vector3d::Constant(h)).prod() - V);
  CHECK(p.centre.norm() <= 1e-12 * E.maxCoeff());
  const double r = 0.005;
  const ShapeSpec round = gf::box_shape(E, r);
  const Vector3d core = E - Vector3d::Constant(2 * r);
  for (const Vector3d& x : round.parts[0]) CHECK((x.cwiseAbs() - core / 2).norm() <= 1e-16);
  const gf::MassProperties q = props(round, h);
  const double W = box_q(core).at(r);
  const Vector3d g = Vector3d::Constant(h);
  CHECK(std::abs(q.volume - W) <= std::max(box_q(core + g).at(r) - W, W - box_q(core - g).at(r)));
  CHECK(q.centre.norm() <= 1e-12 * E.maxCoeff());
  CHECK(inset_error(sharp.parts[0], round.parts[0], r) <= 1e-15);
}

TEST_CASE("body_shapes: a triangular prism's volume and centre, sharp and dilated", "[bodies]") {
  // Equilateral section of side a, length l: V = sqrt(3)/4 a^2 l, centroid at the origin. The core
  // of the dilated prism has side a - 2 sqrt(3) r (the inradius a / (2 sqrt 3) less r) and length
  // l - 2r; its volume is the prism's Steiner polynomial at r. Tolerances as in the file's head.
  // Measured (h = 0.5 mm): sharp volume 1.1e-2 of V (bound 0.12), centre 1.7e-5 m (bound
  // 7.3e-3 m); dilated 7.5e-4 (bound 0.11), centre 4.8e-6 m (bound 6.0e-3 m).
  const double a = 0.03, l = 0.05, r = 0.003, h = 0.0005, s = grid_s(h);
  for (const double radius : {0.0, r}) {
    INFO("r = " << radius);
    const ShapeSpec prism = gf::triangular_prism_shape(a, l, radius);
    REQUIRE(prism.parts.size() == 1);
    REQUIRE(prism.parts[0].size() == 6);
    const double ac = a - 2.0 * std::sqrt(3.0) * radius, lc = l - 2.0 * radius;
    const Quermass core = prism_q(std::sqrt(3.0) / 4.0 * ac * ac, 3.0 * ac, lc);
    const Polygon tri = section(prism.parts[0]);
    CHECK(std::abs(perimeter(tri) - 3.0 * ac) <= 1e-15);
    const double V = core.at(radius), E = core.at(radius + s) - V;
    const gf::MassProperties p = props(prism, h);
    CHECK(std::abs(p.volume - V) <= E);
    CHECK(p.centre.norm() <= 2.0 * E * (reach(prism, Vector3d::Zero()) + radius + s) / p.volume);
    if (radius > 0) CHECK(inset_error(gf::triangular_prism_shape(a, l, 0.0).parts[0], prism.parts[0], radius) <= 1e-15);
  }
}

TEST_CASE("body_shapes: the up-down cone's parts against the frustum's closed forms", "[bodies]") {
  // Each part a regular n-gonal frustum: V = h/3 (A1 + A2 + sqrt(A1 A2)), centroid at
  // h (A1 + 2 sqrt(A1 A2) + 3 A2) / (4 (A1 + sqrt(A1 A2) + A2)) from the wide end. Joined at the
  // narrow ends the two parts meet on z = 0 and do not overlap (each lies on its own side, dilated
  // too: its core stops r short of z = 0), so the element's volume is twice a part's; both joins are
  // symmetric about z = 0, so the element's centre is the origin. Dilated: the core is the frustum
  // with every face moved in by r, volume W(core, r) (Steiner, with the frustum's edges' external
  // angles). Measured (h = 1 mm): part volume 1.3e-3 of V (bound 0.22), its centre 1.0e-5 m off
  // the closed form (bound 1.0e-2 m); element 1.3e-3 (bound 0.22), centre 8.4e-7 m (bound
  // 1.6e-2 m); dilated element 2.4e-3 (bound 0.20); double pyramid 7.4e-4 (bound 0.28).
  const gf::UpDownCone cone{0.02, 0.006, 0.03, 12, gf::UpDownCone::Join::narrow_ends};
  const Frustum f{12, 0.02, 0.006, 0.03};
  const double h = 0.001, s = grid_s(h);
  const ShapeSpec el = gf::up_down_cone_shape(cone, 0.0);
  REQUIRE(el.parts.size() == 2);
  CHECK(el.parts[0].size() == 24);
  const ShapeSpec upper{{el.parts[1]}, 0.0};
  const gf::MassProperties p = props(upper, h);
  const Quermass q = f.quermass();
  const double E = q.at(s) - q.V;
  CHECK(std::abs(p.volume - f.volume()) <= E);
  const Vector3d c(0, 0, f.h - f.centroid());  // the upper part's wide end is at z = h
  CHECK((p.centre - c).norm() <= 2.0 * E * (reach(upper, c) + s) / p.volume);
  const gf::MassProperties pe = props(el, h);
  CHECK(std::abs(pe.volume - 2.0 * f.volume()) <= 2.0 * E);
  CHECK(pe.centre.norm() <= 2.0 * 2.0 * E * (reach(el, Vector3d::Zero()) + s) / pe.volume);

  const double r = 0.002;
  const ShapeSpec round = gf::up_down_cone_shape(cone, r);
  const Quermass core = f.inset(r).quermass();
  CHECK(inset_error(el.parts[0], round.parts[0], r) <= 1e-15);
  CHECK(inset_error(el.parts[1], round.parts[1], r) <= 1e-15);
  const gf::MassProperties pr = props(round, h);
  CHECK(std::abs(pr.volume - 2.0 * core.at(r)) <= 2.0 * (core.at(r + s) - core.at(r)));
  CHECK(pr.centre.norm() <= 1e-15 + 4.0 * (core.at(r + s) - core.at(r)) * (reach(round, Vector3d::Zero()) + r + s) / pr.volume);

  // Joined at the wide ends with pointed tips: a double pyramid of two n-gonal pyramids.
  const gf::UpDownCone bi{0.02, 0.0, 0.03, 6, gf::UpDownCone::Join::wide_ends};
  const Frustum pyr{6, 0.02, 0.0, 0.03};
  const ShapeSpec b = gf::up_down_cone_shape(bi, 0.0);
  CHECK(b.parts[0].size() == 7);
  const gf::MassProperties pb = props(b, h);
  CHECK(pyr.volume() == Approx(0.02 * 0.02 * 3.0 * std::sqrt(3.0) / 2.0 * 0.03 / 3.0).epsilon(1e-14));
  CHECK(std::abs(pb.volume - 2.0 * pyr.volume()) <= 2.0 * (pyr.quermass().at(s) - pyr.volume()));
}

TEST_CASE("body_shapes: the up-down cone is waisted, and bad cones are refused", "[bodies]") {
  // Joined at the narrow ends the element is concave: a point just outside the neck, inside the
  // convex hull of the two wide ends, lies outside both parts.
  const gf::UpDownCone cone{0.02, 0.006, 0.03, 12, gf::UpDownCone::Join::narrow_ends};
  const ShapeSpec el = gf::up_down_cone_shape(cone, 0.0);
  CHECK(clearance(el, {0.012, 0, 0}) > 0.005);
  CHECK(clearance(el, {0, 0, 0}) <= 0.0);
  gf::UpDownCone pointed = cone;
  pointed.neck_radius = 0;
  CHECK_THROWS_AS(gf::up_down_cone_shape(pointed, 0.0), std::invalid_argument);
  gf::UpDownCone few = cone;
  few.facets = 2;
  CHECK_THROWS_AS(gf::up_down_cone_shape(few, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::up_down_cone_shape(cone, 0.01), std::invalid_argument);  // the neck's core vanishes
  CHECK_THROWS_AS(gf::box_shape({0.01, 0.02, 0.03}, 0.005), std::invalid_argument);
  CHECK_NOTHROW(gf::box_shape({0.01, 0.02, 0.03}, 0.0049));
  const std::vector<Vector2d> concave{{0, 0}, {1, 0}, {0.2, 0.2}, {0, 1}};
  CHECK_THROWS_AS(gf::prism_shape(concave, 1.0, 0.0), std::invalid_argument);
  const std::vector<Vector2d> clockwise{{0, 0}, {0, 1}, {1, 0}};
  CHECK_THROWS_AS(gf::prism_shape(clockwise, 1.0, 0.0), std::invalid_argument);
}

// ---- Letters -------------------------------------------------------------------------------------------

TEST_CASE("body_shapes: each letter's volume and centre against its strokes less their overlaps", "[bodies]") {
  // Every letter is a prism of depth W over the union of its strokes' sections, so V = W * area of
  // that union, found here by inclusion and exclusion over the sections (clipped polygons); for O, T,
  // C and Z also written out from the layout (the strokes' sum less the s x s corners or the
  // slanted stroke's w x s ends in the bars). Bounds per stroke from its prism's Steiner polynomial
  // (file head). Measured (h = 1.3 mm, V relative): O 4.1e-2 (bound 0.22), T 4.0e-2 (0.19),
  // Z 4.1e-2 (0.21), K 4.4e-2 (0.20), A 4.4e-2 (0.21), C 4.0e-2 (0.21) (the aligned faces err one
  // way, about half a voxel layer); centres within 1.1e-4 m of the sections' (bounds 0.041 to
  // 0.045 m). At h = 1 mm every face of O, T and C lies on a voxel face: volume to 4e-16.
  const gf::LetterSize z;
  const double L = z.width, H = z.height, W = z.depth, s = z.stroke, h = 0.0013, g = grid_s(h);
  for (const char letter : {'O', 'T', 'Z', 'K', 'A', 'C'}) {
    INFO("letter " << letter);
    const ShapeSpec shape = gf::letter_shape(letter, z, 0.0);
    std::vector<Polygon> sections;
    double E = 0;
    for (const auto& part : shape.parts) {
      sections.push_back(section(part));
      REQUIRE(sections.back().size() == 4);
      CHECK(width(sections.back()) == Approx(s).epsilon(1e-12));
      const Quermass q = prism_q(moments(sections.back()).area, perimeter(sections.back()), W);
      E += q.at(g) - q.V;
    }
    const AreaMoment u = union_moments(sections);
    const double w = sections.back()[1].x() - sections.back()[0].x();  // Z: the slanted stroke's ends
    if (letter == 'O') CHECK(u.area == Approx(2 * L * s + 2 * H * s - 4 * s * s).epsilon(1e-12));
    if (letter == 'T') CHECK(u.area == Approx(L * s + H * s - s * s).epsilon(1e-12));
    if (letter == 'C') CHECK(u.area == Approx(H * s + 2 * L * s - 2 * s * s).epsilon(1e-12));
    if (letter == 'Z') CHECK(u.area == Approx(2 * L * s + w * H - 2 * w * s).epsilon(1e-12));
    const double V = W * u.area;
    const Vector3d c(u.first.x() / u.area, u.first.y() / u.area, 0.0);
    const gf::MassProperties p = props(shape, h);
    CHECK(std::abs(p.volume - V) <= E);
    CHECK((p.centre - c).norm() <= 2.0 * E * (reach(shape, c) + g) / p.volume);
    if (letter == 'O' || letter == 'T' || letter == 'C') {
      // Every face on a voxel face: the voxels are exactly the union, each overlap counted once.
      const gf::MassProperties q = props(shape, 0.001);
      CHECK(q.volume == Approx(V).epsilon(1e-12));
      CHECK((q.centre - c).norm() <= 1e-12 * H);
    }
  }
}

TEST_CASE("body_shapes: the letters' outline, holes, mouths and notches", "[bodies]") {
  // Packing-relevant facts of the layouts: each letter fills its L x H x W box; O has a hole through
  // it (the line along z through its centre misses every stroke, 20 mm from the nearest); A a
  // triangular hole above its crossbar; C a mouth open to +x; T, Z and K notches inside their box.
  // Dilated (r = 2 mm, the cores moved in by r) the outline, the holes and their clearances stay:
  // those are concave corners, which the rounding leaves sharp.
  const gf::LetterSize z;
  const double L = z.width, H = z.height, W = z.depth, s = z.stroke;
  for (const double r : {0.0, 0.002}) {
    INFO("r = " << r);
    for (const char letter : {'O', 'T', 'Z', 'K', 'A', 'C'}) {
      INFO("letter " << letter);
      const ShapeSpec shape = gf::letter_shape(letter, z, r);
      Vector3d lo = Vector3d::Constant(1e300), hi = -lo;
      for (const auto& part : shape.parts)
        for (const Vector3d& x : part) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
      // Sharp, the box exactly; dilated, within it (acute corners, rounded, recede further).
      const Vector3d half(L / 2 - r, H / 2 - r, W / 2 - r);
      CHECK((hi - half).maxCoeff() <= 1e-15);
      CHECK((-lo - half).maxCoeff() <= 1e-15);
      if (r == 0) CHECK(std::max((hi - half).norm(), (lo + half).norm()) <= 1e-15);
      if (r > 0) {
        const ShapeSpec sharp = gf::letter_shape(letter, z, 0.0);
        for (std::size_t i = 0; i < shape.parts.size(); ++i)
          CHECK(inset_error(sharp.parts[i], shape.parts[i], r) <= 1e-15);
      }
    }
    const ShapeSpec O = gf::letter_shape('O', z, r);
    // On the faces (z = +-W/2) the hole's edges are convex edges of the strokes, rounded: further.
    CHECK(clearance(O, {0, 0, 0}) == Approx(L / 2 - s).epsilon(1e-12));
    for (const double zz : {-W / 2, W / 2}) CHECK(clearance(O, {0, 0, zz}) >= L / 2 - s - 1e-15);
    CHECK(clearance(gf::letter_shape('A', z, r), {0, -0.02, 0}) > 0.005);
    const ShapeSpec C = gf::letter_shape('C', z, r);
    for (double x = -L / 2 + s + 0.001; x <= L / 2; x += 0.005) CHECK(clearance(C, {x, 0, 0}) > 0.0);
    CHECK(clearance(gf::letter_shape('T', z, r), {L / 4, -H / 4, 0}) > 0.009);
    CHECK(clearance(gf::letter_shape('Z', z, r), {L / 4, -H / 4, 0}) > 0.01);
    CHECK(clearance(gf::letter_shape('K', z, r), {L / 4, 0, 0}) > 0.01);
  }
  // Points on a stroke are inside: the letter is not empty where it should be solid.
  CHECK(clearance(gf::letter_shape('O', z, 0.0), {-L / 2 + s / 2, 0, 0}) <= 0.0);
  CHECK(clearance(gf::letter_shape('A', z, 0.0), {0, H / 2 - 0.005, 0}) <= 0.0);
  CHECK_THROWS_AS(gf::letter_shape('Q', z, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::letter_shape('O', gf::LetterSize{0.1, 0.18, 0.03, 0.05}, 0.0), std::invalid_argument);
  CHECK_THROWS_AS(gf::letter_shape('O', z, 0.015), std::invalid_argument);
}
