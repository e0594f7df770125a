#include "systems/coupling/rotational_drag.hpp"

#include <cmath>
#include <numbers>

#include "engine/intrinsics.hpp"

#include <Eigen/Dense>

namespace gf {

double rotational_drag_coefficient(double re) {
  if (re <= 32.0) return 64.0 * std::numbers::pi / re;
  return 12.9 / std::sqrt(re) + 128.4 / re;
}

V3<double> rotational_drag_torque(const V3<double>& omega_rel, double d, const LiquidProps& liquid) {
  const double w = std::sqrt(dot(omega_rel, omega_rel));
  if (!(w > 0)) return {0, 0, 0};
  const double nu = liquid.viscosity / liquid.density;
  const double re = w * d * d / nu;
  const double r = 0.5 * d;
  const double k = 0.5 * liquid.density * r * r * r * r * r * rotational_drag_coefficient(re) * w;
  return (-k) * omega_rel;
}

std::vector<V3<double>> curl_at_grains(const GrainShares& s, const PointSet& grains, const PointSet& nodes,
                                       const PointSet& velocity, const PeriodicAxis& periodic) {
  const std::size_t n = grains.size();
  std::vector<V3<double>> curl(n, V3<double>{0, 0, 0});
  const double period = periodic.hi - periodic.lo;
  for (std::size_t p = 0; p < n; ++p) {
    if (s.start[p + 1] - s.start[p] < 4) continue;
    // Weighted means first, then the fit about them: u - u_mean = G (x - x_mean).
    Eigen::Vector3d xm = Eigen::Vector3d::Zero(), um = Eigen::Vector3d::Zero();
    double wsum = 0;
    auto offset = [&](std::uint32_t k) {
      Eigen::Vector3d d(nodes.x[k] - grains.x[p], nodes.y[k] - grains.y[p], nodes.z[k] - grains.z[p]);
      if (periodic.axis >= 0) d[periodic.axis] -= period * std::round(d[periodic.axis] / period);
      return d;
    };
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) {
      const std::uint32_t k = s.node[e];
      xm += s.share[e] * offset(k);
      um += s.share[e] * Eigen::Vector3d(velocity.x[k], velocity.y[k], velocity.z[k]);
      wsum += s.share[e];
    }
    if (!(wsum > 0)) continue;
    xm /= wsum;
    um /= wsum;
    Eigen::Matrix3d M = Eigen::Matrix3d::Zero(), B = Eigen::Matrix3d::Zero();
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) {
      const std::uint32_t k = s.node[e];
      const Eigen::Vector3d dx = offset(k) - xm;
      const Eigen::Vector3d du = Eigen::Vector3d(velocity.x[k], velocity.y[k], velocity.z[k]) - um;
      M += s.share[e] * dx * dx.transpose();
      B += s.share[e] * dx * du.transpose();
    }
    // M G^T = B: row a of G^T is d u / d x_a, so J(b, a) = d u_b / d x_a = (M^-1 B)(a, b).
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(M);
    if (lu.rank() < 3) continue;
    const Eigen::Matrix3d D = lu.solve(B);  // D(a, b) = d u_b / d x_a
    curl[p] = {D(1, 2) - D(2, 1), D(2, 0) - D(0, 2), D(0, 1) - D(1, 0)};
  }
  return curl;
}

}  // namespace gf
