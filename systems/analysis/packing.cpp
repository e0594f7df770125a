#include "systems/analysis/packing.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "systems/bodies/mass_properties.hpp"

namespace gf {

PackingFraction packing_fraction(const Bodies& bodies, const Members& members, const std::array<double, 3>& lo,
                                 const std::array<double, 3>& hi, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("packing: the voxel edge must be positive");
  std::array<std::size_t, 3> dims{};
  double total = 1.0;
  for (int d = 0; d < 3; ++d) {
    if (!(hi[d] > lo[d])) throw std::invalid_argument("packing: the box needs hi > lo on every axis");
    dims[d] = static_cast<std::size_t>(std::max(1.0, std::round((hi[d] - lo[d]) / h)));
    total *= static_cast<double>(dims[d]);
  }
  if (total > static_cast<double>(1u << 30)) throw std::invalid_argument("packing: more than 2^30 voxels: a larger h");
  std::array<double, 3> edge{};
  for (int d = 0; d < 3; ++d) edge[d] = (hi[d] - lo[d]) / static_cast<double>(dims[d]);
  std::vector<std::uint8_t> solid(dims[0] * dims[1] * dims[2], 0);
  for (std::size_t m = 0; m < members.n; ++m) {
    const std::uint32_t b = members.body.row[m];
    if (!bodies.moving(b)) continue;
    const Eigen::Quaterniond q(bodies.q.w[b], bodies.q.x[b], bodies.q.y[b], bodies.q.z[b]);
    const Eigen::Vector3d x(bodies.pos.x[b], bodies.pos.y[b], bodies.pos.z[b]);
    const Eigen::Matrix3d to_body = q.normalized().toRotationMatrix().transpose();
    std::vector<Eigen::Vector3d> v;
    for (std::uint32_t k = 0; k < members.core.count[m]; ++k) {
      const std::uint32_t i = members.core.first[m] + k;
      v.emplace_back(members.vertices.x[i], members.vertices.y[i], members.vertices.z[i]);
    }
    const ConvexCore core(v);
    const double r = members.dilation.r[m];
    // The voxels whose centres the member's bounding sphere can reach.
    const Eigen::Vector3d c(members.centre.x[m], members.centre.y[m], members.centre.z[m]);
    const double reach = members.bound.radius[m];
    std::array<std::size_t, 3> from{}, to{};
    bool empty = false;
    for (int d = 0; d < 3; ++d) {
      const double a = std::floor((c[d] - reach - lo[d]) / edge[d]), z = std::ceil((c[d] + reach - lo[d]) / edge[d]);
      if (z < 0.0 || a >= static_cast<double>(dims[d])) empty = true;
      from[d] = static_cast<std::size_t>(std::max(0.0, a));
      to[d] = static_cast<std::size_t>(std::min(static_cast<double>(dims[d]), std::max(0.0, z)));
    }
    if (empty) continue;
    for (std::size_t k = from[2]; k < to[2]; ++k)
      for (std::size_t j = from[1]; j < to[1]; ++j)
        for (std::size_t i = from[0]; i < to[0]; ++i) {
          std::uint8_t& cell = solid[i + dims[0] * (j + dims[1] * k)];
          if (cell) continue;
          const Eigen::Vector3d p(lo[0] + (static_cast<double>(i) + 0.5) * edge[0],
                                  lo[1] + (static_cast<double>(j) + 0.5) * edge[1],
                                  lo[2] + (static_cast<double>(k) + 0.5) * edge[2]);
          if (core.dilated_contains(to_body * (p - x), r)) cell = 1;
        }
  }
  PackingFraction out;
  out.voxels = solid.size();
  out.solid = static_cast<std::size_t>(std::count(solid.begin(), solid.end(), std::uint8_t{1}));
  out.fraction = static_cast<double>(out.solid) / static_cast<double>(out.voxels);
  return out;
}

}  // namespace gf
