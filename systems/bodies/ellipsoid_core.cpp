// The ellipsoid core (member_core.hpp): points c, c + u_1, c + u_2, c + u_3, the u_i orthogonal
// semi-axes; the solid {c + M s : |s| <= 1}, M = [u_1 u_2 u_3].
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Geometry>

#include "systems/bodies/mass_properties.hpp"
#include "systems/bodies/member_core.hpp"

namespace gf {

using Eigen::Vector3d;

namespace {

// The ellipsoid's frame: centre, unit axes e_i and semi-axes a_i.
struct Frame {
  Vector3d c;
  std::array<Vector3d, 3> e;
  Vector3d a;
};

Frame frame(const CoreView& core) {
  Frame f;
  f.c = core.point(0);
  for (int i = 0; i < 3; ++i) {
    const Vector3d u = core.point(static_cast<std::size_t>(i) + 1) - f.c;
    f.a[i] = u.norm();
    f.e[static_cast<std::size_t>(i)] = u / f.a[i];
  }
  return f;
}

// With q the point in the ellipsoid's frame, the closest surface point is
// x_i = a_i^2 q_i / (t + a_i^2) for the root t >= 0 of F(t) = sum (a_i q_i / (t + a_i^2))^2 - 1, which
// decreases from F(0) > 0 (outside) to F(a_max |q|) <= 0. Bisection to round-off: about 60 halvings.
Vector3d closest_point(const Frame& f, const Vector3d& p) {
  Vector3d q;
  for (int i = 0; i < 3; ++i) q[i] = f.e[static_cast<std::size_t>(i)].dot(p - f.c);
  if (q.cwiseQuotient(f.a).squaredNorm() <= 1.0) return p;
  const auto excess = [&](double t) {
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double v = f.a[i] * q[i] / (t + f.a[i] * f.a[i]);
      s += v * v;
    }
    return s - 1.0;
  };
  double lo = 0, hi = f.a.maxCoeff() * q.norm();
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (excess(mid) > 0 ? lo : hi) = mid;
  }
  const double t = 0.5 * (lo + hi);
  Vector3d x = f.c;
  for (int i = 0; i < 3; ++i) x += f.a[i] * f.a[i] * q[i] / (t + f.a[i] * f.a[i]) * f.e[static_cast<std::size_t>(i)];
  return x;
}

class EllipsoidSolid final : public CoreSolid {
 public:
  explicit EllipsoidSolid(const CoreView& core) : f_(frame(core)) {}
  double distance(const Vector3d& p) const override { return (p - closest_point(f_, p)).norm(); }
  bool dilated_contains(const Vector3d& p, double r) const override {
    // Inside the solid, or inside the sphere round it and within r of the surface.
    double s = 0;
    for (int i = 0; i < 3; ++i) {
      const double q = f_.e[static_cast<std::size_t>(i)].dot(p - f_.c) / f_.a[i];
      s += q * q;
    }
    if (s <= 1.0) return true;
    if (!(r > 0) || (p - f_.c).norm() > f_.a.maxCoeff() + r) return false;
    return distance(p) <= r;
  }

 private:
  Frame f_;
};

}  // namespace

namespace ellipsoid_core {

Vector3d support(const CoreView& core, const Vector3d& d) {
  const Vector3d c = core.point(0);
  const Vector3d u1 = core.point(1) - c, u2 = core.point(2) - c, u3 = core.point(3) - c;
  const Vector3d w(u1.dot(d), u2.dot(d), u3.dot(d));  // M^T d
  const double n = w.norm();
  if (!(n > 0)) return c + u1;
  return c + (w.x() * u1 + w.y() * u2 + w.z() * u3) / n;
}

Vector3d centre(const CoreView& core) { return core.point(0); }

double reach(const CoreView& core, const Vector3d& at) {
  const Frame f = frame(core);
  return (f.c - at).norm() + f.a.maxCoeff();
}

Vector3d closest(const CoreView& core, const Vector3d& p) { return closest_point(frame(core), p); }

std::unique_ptr<CoreSolid> solid(const CoreView& core) { return std::make_unique<EllipsoidSolid>(core); }

// Rings of 24 points at 11 latitudes and the two poles: the hull of their projection lies within
// 1 - cos(7.5 deg) = 0.9 % of the semi-axes inside the true outline.
std::vector<Vector3d> outline(const CoreView& core) {
  const Vector3d c = core.point(0);
  const Vector3d u1 = core.point(1) - c, u2 = core.point(2) - c, u3 = core.point(3) - c;
  std::vector<Vector3d> out{c + u3, c - u3};
  constexpr int kRings = 11, kAround = 24;
  for (int i = 1; i <= kRings; ++i) {
    const double th = std::numbers::pi * i / (kRings + 1);
    for (int j = 0; j < kAround; ++j) {
      const double ph = 2 * std::numbers::pi * j / kAround;
      out.push_back(c + std::sin(th) * std::cos(ph) * u1 + std::sin(th) * std::sin(ph) * u2 + std::cos(th) * u3);
    }
  }
  return out;
}

void check(const CoreView& core) {
  for (std::size_t i = 0; i < core.size(); ++i)
    if (!core.point(i).allFinite()) throw std::invalid_argument("a point is not finite");
  const Vector3d c = core.point(0);
  std::array<Vector3d, 3> u;
  for (std::size_t i = 0; i < 3; ++i) {
    u[i] = core.point(i + 1) - c;
    if (!(u[i].norm() > 0)) throw std::invalid_argument("a semi-axis has zero length");
  }
  // Orthogonal to 1e-9 of the axes' lengths: far above the round-off of a rotation, far below a
  // slant anyone would give on purpose.
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = i + 1; j < 3; ++j)
      if (std::abs(u[i].dot(u[j])) > 1e-9 * u[i].norm() * u[j].norm())
        throw std::invalid_argument("its semi-axes are not orthogonal");
}

std::vector<Vector3d> points(const Vector3d& semi_axes) {
  return {Vector3d::Zero(), Vector3d(semi_axes.x(), 0, 0), Vector3d(0, semi_axes.y(), 0), Vector3d(0, 0, semi_axes.z())};
}

}  // namespace ellipsoid_core

MassProperties ellipsoid_mass_properties(const Eigen::Vector3d& semi_axes, double rho) {
  if (!(semi_axes.minCoeff() > 0) || !semi_axes.allFinite() || !(rho > 0) || !std::isfinite(rho))
    throw std::invalid_argument("an ellipsoid needs positive, finite semi-axes and density");
  const double a = semi_axes.x(), b = semi_axes.y(), c = semi_axes.z();
  MassProperties p;
  p.volume = 4.0 / 3.0 * std::numbers::pi * a * b * c;
  p.mass = rho * p.volume;
  p.centre = Vector3d::Zero();
  const Vector3d moments(p.mass / 5 * (b * b + c * c), p.mass / 5 * (a * a + c * c), p.mass / 5 * (a * a + b * b));
  p.inertia = moments.asDiagonal();
  // Ascending, each with its axis; the third axis flipped where needed for det +1.
  std::array<int, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) { return moments[i] < moments[j]; });
  for (int k = 0; k < 3; ++k) {
    p.moments[k] = moments[order[static_cast<std::size_t>(k)]];
    p.axes.col(k) = Vector3d::Unit(order[static_cast<std::size_t>(k)]);
  }
  if (p.axes.determinant() < 0) p.axes.col(2) *= -1.0;
  return p;
}

}  // namespace gf
