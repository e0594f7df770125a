#include "systems/fill/region.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace gf {
namespace {

using Vec = std::array<double, 3>;

double dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double norm(const Vec& a) { return std::sqrt(dot(a, a)); }
bool finite(const Vec& a) {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}
Vec normalised(const Vec& a) {
  const double n = norm(a);
  // A zero or non-finite direction is left as it is for problem() to report.
  if (!(n > 0.0) || !std::isfinite(n)) return a;
  return {a[0] / n, a[1] / n, a[2] / n};
}

constexpr double kPi = std::numbers::pi;

// Area of the part {q1 <= d} of a disc of radius R (a circular segment, or all/none of it).
double segment_area(double R, double d) {
  if (d <= -R) return 0.0;
  if (d >= R) return kPi * R * R;
  return R * R * std::acos(-d / R) + d * std::sqrt(R * R - d * d);
}

// Antiderivative of segment_area in d, zero at d = -R; closed form so the cut-cylinder volume is
// exact rather than a quadrature whose accuracy depends on where the plane crosses the disc.
double segment_area_integral(double R, double d) {
  if (d <= -R) return 0.0;
  if (d >= R) return kPi * R * R * R + kPi * R * R * (d - R);
  const double w = R * R - d * d;
  return R * R * d * std::acos(-d / R) + R * R * std::sqrt(w) - w * std::sqrt(w) / 3.0;
}

}  // namespace

Region Region::box(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  Region r;
  r.kind = Kind::Box;
  r.lo = lo;
  r.hi = hi;
  return r;
}

Region Region::cylinder(const std::array<double, 3>& center, const std::array<double, 3>& axis,
                        double radius, double length, double max_height,
                        const std::array<double, 3>& up) {
  Region r;
  r.kind = Kind::Cylinder;
  r.center = center;
  r.axis = normalised(axis);
  r.radius = radius;
  r.length = length;
  r.max_height = max_height;
  r.up = normalised(up);
  return r;
}

double Region::volume() const {
  if (kind == Kind::Box) {
    double v = 1.0;
    for (int i = 0; i < 3; ++i) v *= std::max(0.0, hi[i] - lo[i]);
    return v;
  }
  const double R = radius;
  const double L = length;
  const double full = kPi * R * R * L;
  if (max_height == std::numeric_limits<double>::infinity()) return full;

  // Height of a point at axial coordinate s and in-disc coordinate q1 (along the part of `up`
  // across the axis) is a*s + p*q1.
  const double a = dot(up, axis);
  const Vec perp{up[0] - a * axis[0], up[1] - a * axis[1], up[2] - a * axis[2]};
  const double p = norm(perp);
  const double H = max_height;
  double v = 0.0;
  if (p < 1e-12) {
    // `up` along the axis: the plane cuts the cylinder across, leaving a shorter cylinder.
    const double cut = std::clamp(H / a, -0.5 * L, 0.5 * L);
    v = kPi * R * R * (a > 0.0 ? cut + 0.5 * L : 0.5 * L - cut);
  } else {
    const double x = std::abs(a) * L / (p * R);
    if (x < 1e-5) {
      // Nearly level axis: the closed form below would divide a cancelling difference by a
      // tiny a; the segment area barely changes along the axis, so the midpoint is exact to ~x^2.
      v = L * segment_area(R, H / p);
    } else {
      const double d_lo = (H + a * 0.5 * L) / p;  // at s = -L/2
      const double d_hi = (H - a * 0.5 * L) / p;  // at s = +L/2
      v = (p / a) * (segment_area_integral(R, d_lo) - segment_area_integral(R, d_hi));
    }
  }
  return std::clamp(v, 0.0, full);
}

bool Region::contains_sphere(const std::array<double, 3>& p, double r) const {
  if (kind == Kind::Box) {
    for (int i = 0; i < 3; ++i) {
      if (!(p[i] - r >= lo[i] && p[i] + r <= hi[i])) return false;
    }
    return true;
  }
  const Vec d{p[0] - center[0], p[1] - center[1], p[2] - center[2]};
  const double s = dot(d, axis);
  if (!(std::abs(s) + r <= 0.5 * length)) return false;
  // The radial vector itself rather than |d|^2 - s^2, which cancels badly near the axis ends.
  const Vec q{d[0] - s * axis[0], d[1] - s * axis[1], d[2] - s * axis[2]};
  if (!(norm(q) + r <= radius)) return false;
  if (max_height != std::numeric_limits<double>::infinity() && !(dot(d, up) + r <= max_height)) {
    return false;
  }
  return true;
}

std::array<double, 3> Region::bbox_lo() const {
  if (kind == Kind::Box) return lo;
  Vec out{};
  for (int i = 0; i < 3; ++i) {
    const double half = std::abs(axis[i]) * 0.5 * length +
                        radius * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
    out[i] = center[i] - half;
    if (up[i] <= -1.0 + 1e-12 && std::isfinite(max_height)) {
      out[i] = std::max(out[i], center[i] - max_height);
    }
  }
  return out;
}

std::array<double, 3> Region::bbox_hi() const {
  if (kind == Kind::Box) return hi;
  Vec out{};
  for (int i = 0; i < 3; ++i) {
    const double half = std::abs(axis[i]) * 0.5 * length +
                        radius * std::sqrt(std::max(0.0, 1.0 - axis[i] * axis[i]));
    out[i] = center[i] + half;
    if (up[i] >= 1.0 - 1e-12 && std::isfinite(max_height)) {
      out[i] = std::min(out[i], center[i] + max_height);
    }
  }
  return out;
}

std::string Region::problem() const {
  std::ostringstream os;
  if (kind == Kind::Box) {
    if (!finite(lo) || !finite(hi)) {
      os << "box corners must be finite. Fix: give lo and hi as three finite coordinates in m";
    } else if (!(hi[0] > lo[0] && hi[1] > lo[1] && hi[2] > lo[2])) {
      os << "box has hi <= lo in some coordinate (lo = " << lo[0] << ", " << lo[1] << ", " << lo[2]
         << "; hi = " << hi[0] << ", " << hi[1] << ", " << hi[2]
         << "). Fix: make every coordinate of hi larger than the same coordinate of lo";
    } else if (max_height != std::numeric_limits<double>::infinity()) {
      os << "max_height applies to cylinders only. Fix: cut a box by lowering hi";
    }
    return os.str();
  }
  if (!finite(center)) {
    os << "cylinder centre must be finite. Fix: give three finite coordinates in m";
  } else if (!finite(axis) || std::abs(norm(axis) - 1.0) > 1e-9) {
    os << "cylinder axis must be a unit vector (|axis| = " << norm(axis)
       << "). Fix: build the region with Region::cylinder, which normalises it";
  } else if (!(radius > 0.0) || !std::isfinite(radius)) {
    os << "cylinder radius " << radius << " m is not positive. Fix: give a radius > 0 in m";
  } else if (!(length > 0.0) || !std::isfinite(length)) {
    os << "cylinder length " << length << " m is not positive. Fix: give a length > 0 in m";
  } else if (std::isnan(max_height) || max_height == -std::numeric_limits<double>::infinity()) {
    os << "cylinder max_height is " << max_height
       << ". Fix: give a height in m above the centre along up, or leave it out for no limit";
  } else if (std::isfinite(max_height) && (!finite(up) || std::abs(norm(up) - 1.0) > 1e-9)) {
    os << "up must be a unit vector (|up| = " << norm(up)
       << "). Fix: build the region with Region::cylinder, which normalises it";
  } else if (!(volume() > 0.0)) {
    os << "max_height " << max_height
       << " m leaves nothing of the cylinder. Fix: raise max_height (it is measured from the "
          "centre along up, so 0 keeps the lower half)";
  }
  return os.str();
}

}  // namespace gf
