#include "systems/analysis/free_surface.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "systems/analysis/line_fit.hpp"

namespace gf {

namespace {

// The third-highest grain top per column, and how many grains each column holds.
struct Columns {
  double u0 = 0, width = 0;
  std::vector<std::array<double, 3>> tops;
  std::vector<int> count;
  double centre(int c) const { return u0 + (c + 0.5) * width; }
};

Columns column_tops(const SurfaceGrains& g, const DrumSection& drum) {
  const double R = drum.radius;
  double r_max = 0;
  for (const double r : g.r) r_max = std::max(r_max, r);
  Columns cols;
  // Two large diameters, but at least ten columns across a drum that is small for its grains.
  cols.width = std::max(std::min(4.0 * r_max, R / 10.0), R / 50.0);
  cols.u0 = -R;
  const int n = static_cast<int>(std::ceil(2.0 * R / cols.width));
  cols.tops.assign(static_cast<std::size_t>(n), {-INFINITY, -INFINITY, -INFINITY});
  cols.count.assign(static_cast<std::size_t>(n), 0);
  for (std::size_t i = 0; i < g.x.size(); ++i) {
    const double u = drum.u(g.x[i], g.y[i], g.z[i]), v = drum.v(g.x[i], g.y[i], g.z[i]);
    // The column is found in double and checked before the conversion: a grain far outside the
    // drum (a corrupt state) must not overflow the int.
    const double column = std::floor((u + R) / cols.width);
    if (!(column >= 0 && column < n)) continue;
    const auto c = static_cast<std::size_t>(column);
    auto& t = cols.tops[c];
    const double top = v + g.r[i];
    ++cols.count[c];
    if (top > t[0])
      t = {top, t[0], t[1]};
    else if (top > t[1])
      t = {t[0], top, t[1]};
    else if (top > t[2])
      t[2] = top;
  }
  return cols;
}

// The parabola's coefficient of u^2 through the points (u - um, v), least squares; NaN when the
// points do not fix a parabola (fewer than three distinct u).
double parabola_curvature(const std::vector<std::array<double, 2>>& pts, double um) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (const auto& [u, v] : pts) {
    const Eigen::Vector3d p(1.0, u - um, (u - um) * (u - um));
    a += p * p.transpose();
    b += p * v;
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(a);
  if (pts.size() < 3 || lu.rank() < 3) return FreeSurface::kNaN;
  return lu.solve(b)(2);
}

}  // namespace

FreeSurface free_surface(const SurfaceGrains& g, const DrumSection& drum, const FreeSurfaceSettings& s) {
  const std::size_t n = g.x.size();
  if (g.y.size() != n || g.z.size() != n || g.r.size() != n)
    throw std::invalid_argument("free surface: grain columns differ in length");
  const bool moving = !g.vx.empty();
  if (moving && (g.vx.size() != n || g.vy.size() != n || g.vz.size() != n))
    throw std::invalid_argument("free surface: velocity columns differ in length from the positions");
  if (!(drum.radius > 0) || !(s.depth_diameters > 0)) throw std::invalid_argument("free surface: settings out of range");

  FreeSurface out;
  const Columns cols = column_tops(g, drum);
  int lo = -1, hi = -1;
  for (int c = 0; c < static_cast<int>(cols.count.size()); ++c)
    if (cols.count[c] >= 3) {
      if (lo < 0) lo = c;
      hi = c;
    }
  if (lo < 0) return out;
  // The middle 60 % of the bed's width: whole columns inside [a, b].
  const double full = (hi - lo + 1) * cols.width;
  const double a = cols.u0 + lo * cols.width + 0.2 * full, b = cols.u0 + (hi + 1) * cols.width - 0.2 * full;
  LineFit fit;
  std::vector<std::array<double, 2>> pts;
  for (int c = lo; c <= hi; ++c) {
    const double uc = cols.centre(c);
    if (cols.count[c] < 3 || uc - 0.5 * cols.width < a || uc + 0.5 * cols.width > b) continue;
    fit.add(uc, cols.tops[c][2]);
    pts.push_back({uc, cols.tops[c][2]});
  }
  const double slope = fit.slope();
  if (fit.points() < 3 || std::isnan(slope)) return out;
  out.angle = std::atan(slope);
  out.level = fit.intercept();
  out.span = b - a;
  out.bulge = -parabola_curvature(pts, 0.5 * (a + b)) * 0.25 * out.span * out.span;
  if (!moving) return out;

  // The layer: grains in the span whose tops lie within the depth of the line.
  double r_max = 0;
  for (const double r : g.r) r_max = std::max(r_max, r);
  const double depth = s.depth_diameters * 2.0 * r_max, cos_a = std::cos(out.angle), sin_a = std::sin(out.angle);
  // Down the line, in the lab frame: -(cos a right + sin a up).
  const Vec3d down{-(cos_a * drum.right.x + sin_a * drum.up.x), -(cos_a * drum.right.y + sin_a * drum.up.y),
                   -(cos_a * drum.right.z + sin_a * drum.up.z)};
  double vol = 0, flux = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = drum.u(g.x[i], g.y[i], g.z[i]);
    if (!(u >= a && u <= b)) continue;
    const double top = drum.v(g.x[i], g.y[i], g.z[i]) + g.r[i];
    if (!(std::abs(top - (out.level + slope * u)) <= depth)) continue;
    const double w = g.r[i] * g.r[i] * g.r[i];
    vol += w;
    flux += w * (g.vx[i] * down.x + g.vy[i] * down.y + g.vz[i] * down.z);
    ++out.layer_grains;
  }
  if (vol > 0) out.speed = flux / vol;
  return out;
}

}  // namespace gf
