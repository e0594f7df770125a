#include "systems/output/body_picture.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>

#include "systems/bodies/member_core.hpp"

namespace gf {

namespace {

// Okabe & Ito (2008), "Color Universal Design".
constexpr std::array<Rgb, 7> kGroups{{{0, 114, 178},
                                      {213, 94, 0},
                                      {0, 158, 115},
                                      {230, 159, 0},
                                      {204, 121, 167},
                                      {86, 180, 233},
                                      {240, 228, 66}}};
constexpr Rgb kFixed = kFixedGrey;

struct P2 {
  double x, y;
};

double cross(const P2& o, const P2& a, const P2& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

// Andrew's monotone chain: the hull counter-clockwise in (x, y), without repeated points.
std::vector<P2> convex_hull(std::vector<P2> p) {
  std::sort(p.begin(), p.end(), [](const P2& a, const P2& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  if (p.size() < 3) return p;
  std::vector<P2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double segment_distance(const P2& q, const P2& a, const P2& b) {
  const double ex = b.x - a.x, ey = b.y - a.y, len2 = ex * ex + ey * ey;
  const double t = len2 > 0 ? std::clamp(((q.x - a.x) * ex + (q.y - a.y) * ey) / len2, 0.0, 1.0) : 0.0;
  return std::hypot(q.x - a.x - t * ex, q.y - a.y - t * ey);
}

// Signed distance from q to the convex polygon h (counter-clockwise in a y-up frame): negative
// inside, minus the distance to the nearest edge.
double polygon_distance(const P2& q, const std::vector<P2>& h) {
  if (h.size() == 1) return std::hypot(q.x - h[0].x, q.y - h[0].y);
  bool inside = h.size() >= 3;
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < h.size(); ++i) {
    const P2& a = h[i];
    const P2& b = h[(i + 1) % h.size()];
    if (cross(a, b, q) < 0) inside = false;
    d = std::min(d, segment_distance(q, a, b));
  }
  return inside ? -d : d;
}

Rgb scaled(const Rgb& c, double f) {
  return {static_cast<std::uint8_t>(std::lround(c[0] * f)), static_cast<std::uint8_t>(std::lround(c[1] * f)),
          static_cast<std::uint8_t>(std::lround(c[2] * f))};
}

// Nearer to the viewer is larger: +z for a view along -z, -x for a view along +x.
double nearness(int view, const Eigen::Vector3d& x) { return view == 2 ? x.z() : -x.x(); }

}  // namespace

Rgb group_colour(int group) { return kGroups[static_cast<std::size_t>(std::abs(group)) % kGroups.size()]; }
Rgb layer_colour(int layer) { return layer % 2 == 0 ? kGroups[0] : kGroups[1]; }

BodyView body_view(const Bodies& bodies, const Members& members, int view_axis, int size, double lowest) {
  if (view_axis != 0 && view_axis != 2) throw std::invalid_argument("body picture: the view is along x or z");
  BodyView v;
  v.view = view_axis;
  v.right = view_axis == 2 ? 0 : 2;
  v.up = 1;
  v.size = size;
  std::array<double, 3> lo, hi;
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t m = 0; m < members.n; ++m) {
    const std::uint32_t b = members.body.row[m];
    if (bodies.motion.state[b] == static_cast<std::uint8_t>(Motion::removed)) continue;
    const double c[3] = {members.centre.x[m], members.centre.y[m], members.centre.z[m]};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c[k] - members.bound.radius[m]);
      hi[k] = std::max(hi[k], c[k] + members.bound.radius[m]);
    }
  }
  if (!(lo[0] <= hi[0])) throw std::invalid_argument("body picture: no body to frame");
  if (std::isfinite(lowest)) lo[1] = std::min(lo[1], lowest);
  const double margin = 0.05 * std::max(hi[v.right] - lo[v.right], hi[v.up] - lo[v.up]);
  for (int k = 0; k < 3; ++k) lo[k] -= margin, hi[k] += margin;
  v.lo = lo, v.hi = hi;
  return v;
}

Image render_body_picture(const Bodies& bodies, const Members& members, const std::vector<Rgb>& colour,
                          const BodyView& view) {
  if (view.size < 16 || view.size > 8192) throw std::invalid_argument("body picture: size outside [16, 8192] px");
  if (colour.size() < bodies.n) throw std::invalid_argument("body picture: a body has no colour");
  const double w = view.hi[view.right] - view.lo[view.right], h = view.hi[view.up] - view.lo[view.up];
  if (!(w > 0) || !(h > 0)) throw std::invalid_argument("body picture: the view has no extent");
  const double px_per_m = view.size / std::max(w, h);
  Image img;
  img.width = std::max(1, static_cast<int>(std::lround(w * px_per_m)));
  img.height = std::max(1, static_cast<int>(std::lround(h * px_per_m)));
  img.rgb.assign(3 * static_cast<std::size_t>(img.width) * img.height, 255);
  auto to_px = [&](const Eigen::Vector3d& x) {
    return P2{(x[view.right] - view.lo[view.right]) * px_per_m, (x[view.up] - view.lo[view.up]) * px_per_m};
  };

  // Members in drawing order: furthest first (ties by row, so the picture does not depend on sorting).
  std::vector<std::size_t> order;
  std::vector<double> near(members.n, 0.0);
  double near_lo = std::numeric_limits<double>::infinity(), near_hi = -near_lo;
  for (std::size_t m = 0; m < members.n; ++m) {
    if (bodies.motion.state[members.body.row[m]] == static_cast<std::uint8_t>(Motion::removed)) continue;
    near[m] = nearness(view.view, {members.centre.x[m], members.centre.y[m], members.centre.z[m]});
    near_lo = std::min(near_lo, near[m]), near_hi = std::max(near_hi, near[m]);
    order.push_back(m);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return near[a] < near[b]; });

  std::vector<P2> pts;
  for (std::size_t m : order) {
    const std::uint32_t b = members.body.row[m];
    const Eigen::Quaterniond q(bodies.q.w[b], bodies.q.x[b], bodies.q.y[b], bodies.q.z[b]);
    const Eigen::Vector3d x(bodies.pos.x[b], bodies.pos.y[b], bodies.pos.z[b]);
    pts.clear();
    const std::uint32_t first = members.core.first[m], count = members.core.count[m];
    if (members.core.kind[m] == static_cast<std::uint8_t>(CoreKind::hull)) {
      for (std::uint32_t k = first; k < first + count; ++k)
        pts.push_back(to_px(x + q * Eigen::Vector3d(members.vertices.x[k], members.vertices.y[k], members.vertices.z[k])));
    } else {  // a smooth core: points on its surface
      const CoreView core{static_cast<CoreKind>(members.core.kind[m]),
                          std::span<const double>(members.vertices.x.data() + first, count),
                          std::span<const double>(members.vertices.y.data() + first, count),
                          std::span<const double>(members.vertices.z.data() + first, count)};
      for (const Eigen::Vector3d& v : core_outline(core)) pts.push_back(to_px(x + q * v));
    }
    const std::vector<P2> hull = convex_hull(pts);
    const double rp = members.dilation.r[m] * px_per_m;
    // Further members darker, so depth reads in a pile of one colour; a darker rim outlines each.
    const double depth = near_hi > near_lo ? (near[m] - near_lo) / (near_hi - near_lo) : 1.0;
    const Rgb base = bodies.motion.state[b] == static_cast<std::uint8_t>(Motion::fixed) ? kFixed : colour[b];
    const Rgb fill = scaled(base, 0.6 + 0.4 * depth), rim = scaled(base, 0.35);
    double bx0 = std::numeric_limits<double>::infinity(), by0 = bx0, bx1 = -bx0, by1 = -bx0;
    for (const P2& p : hull) bx0 = std::min(bx0, p.x), bx1 = std::max(bx1, p.x), by0 = std::min(by0, p.y), by1 = std::max(by1, p.y);
    const int x0 = std::max(0, static_cast<int>(std::floor(bx0 - rp - 1))),
              x1 = std::min(img.width - 1, static_cast<int>(std::ceil(bx1 + rp + 1)));
    const int y0 = std::max(0, static_cast<int>(std::floor(by0 - rp - 1))),
              y1 = std::min(img.height - 1, static_cast<int>(std::ceil(by1 + rp + 1)));
    for (int py = y0; py <= y1; ++py)
      for (int px = x0; px <= x1; ++px) {
        const double d = polygon_distance({px + 0.5, py + 0.5}, hull);
        const double a = std::clamp(rp + 0.5 - d, 0.0, 1.0);  // one-pixel anti-aliased edge
        if (a <= 0.0) continue;
        // Image rows run downwards; the window's `up` axis upwards.
        std::uint8_t* p = &img.rgb[3 * (static_cast<std::size_t>(img.height - 1 - py) * img.width + px)];
        blend(p, d > rp - 1.0 ? rim : fill, a);
      }
  }
  return img;
}

std::string body_picture_name(double t) {
  char name[64];
  std::snprintf(name, sizeof name, "time_%09.4f.png", t);
  return name;
}

}  // namespace gf
