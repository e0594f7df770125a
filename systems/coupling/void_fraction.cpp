#include "systems/coupling/void_fraction.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "engine/scene.hpp"
#include "systems/broadphase/cell_grid.hpp"

namespace gf {

double smoothing_shape(double q) {
  if (!(q >= 0.0) || q >= 1.0) return 0.0;
  const double a = 1.0 - q;
  return a * a * a * a * (1.0 + 4.0 * q);
}

GrainShares compute_shares(const PointSet& grains, const PointSet& nodes, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("coupling: the smoothing radius must be positive");
  CellGrid grid;
  grid.build(nodes.x, nodes.y, nodes.z, h);
  const std::span<const double> node_coord[3] = {nodes.x, nodes.y, nodes.z};
  GrainShares s;
  s.start.reserve(grains.size() + 1);
  s.start.push_back(0);
  for (std::size_t p = 0; p < grains.size(); ++p) {
    const double q[3] = {grains.x[p], grains.y[p], grains.z[p]};
    // The grain's cell on the grid's axes, and the 27 around it (cells are at least h wide).
    std::int64_t c[3];
    for (int a = 0; a < 3; ++a) c[a] = static_cast<std::int64_t>(std::floor((q[grid.axis[a]] - grid.origin[a]) / grid.cell));
    const std::size_t first = s.node.size();
    double sum = 0.0;
    for (std::int64_t k = c[2] - 1; k <= c[2] + 1; ++k)
      for (std::int64_t j = c[1] - 1; j <= c[1] + 1; ++j)
        for (std::int64_t i = c[0] - 1; i <= c[0] + 1; ++i) {
          if (i < 0 || j < 0 || k < 0 || i >= grid.dims[0] || j >= grid.dims[1] || k >= grid.dims[2]) continue;
          const std::size_t cell = static_cast<std::size_t>(i + grid.dims[0] * (j + grid.dims[1] * k));
          for (std::uint32_t t = grid.start[cell]; t < grid.start[cell + 1]; ++t) {
            const std::uint32_t n = grid.order[t];
            double r2 = 0.0;
            for (int a = 0; a < 3; ++a) r2 += (node_coord[a][n] - q[a]) * (node_coord[a][n] - q[a]);
            const double w = smoothing_shape(std::sqrt(r2) / h);
            if (!(w > 0.0)) continue;
            s.node.push_back(n);
            s.share.push_back(w);
            sum += w;
          }
        }
    if (!(sum > 0.0))
      throw std::runtime_error("coupling: grain " + std::to_string(p) + " at (" + short_number(q[0]) + ", " +
                               short_number(q[1]) + ", " + short_number(q[2]) +
                               ") m has no liquid node within the smoothing radius " + short_number(h) +
                               " m. Fix: a larger smoothing radius, or keep the grains inside the liquid's domain");
    for (std::size_t e = first; e < s.share.size(); ++e) s.share[e] /= sum;
    s.start.push_back(static_cast<std::uint32_t>(s.node.size()));
  }
  return s;
}

GrainShares compute_shares_periodic(const PointSet& grains, const PointSet& nodes, double h, int axis, double lo,
                                    double hi) {
  if (axis < 0 || axis > 2 || !(hi - lo > 0.0)) throw std::invalid_argument("coupling: a periodic axis needs hi > lo");
  const double period = hi - lo;
  // Grains and nodes may stand a little past a face between their lists' rebuilds: both are wrapped
  // into [lo, hi) first, then the nodes within h of a face are imaged across it.
  const auto wrap = [&](double v) { return v - period * std::floor((v - lo) / period); };
  std::vector<double> c[3];
  std::vector<std::uint32_t> origin;
  const std::span<const double> in[3] = {nodes.x, nodes.y, nodes.z};
  const auto add = [&](std::size_t n, double shift) {
    for (int a = 0; a < 3; ++a) c[a].push_back(a == axis ? wrap(in[a][n]) + shift : in[a][n]);
    origin.push_back(static_cast<std::uint32_t>(n));
  };
  for (std::size_t n = 0; n < nodes.size(); ++n) add(n, 0.0);
  for (std::size_t n = 0; n < nodes.size(); ++n) {
    const double v = wrap(in[axis][n]);
    if (v < lo + h) add(n, period);
    if (v > hi - h) add(n, -period);
  }
  std::vector<double> g[3];
  const std::span<const double> gin[3] = {grains.x, grains.y, grains.z};
  for (int a = 0; a < 3; ++a) {
    g[a].assign(gin[a].begin(), gin[a].end());
    if (a == axis)
      for (double& v : g[a]) v = wrap(v);
  }
  GrainShares s = compute_shares(PointSet{g[0], g[1], g[2]}, PointSet{c[0], c[1], c[2]}, h);
  for (std::uint32_t& n : s.node) n = origin[n];
  return s;
}

std::vector<double> solid_volume(const GrainShares& s, std::span<const double> grain_volume, std::size_t nodes) {
  std::vector<double> out(nodes, 0.0);
  for (std::size_t p = 0; p + 1 < s.start.size(); ++p)
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) out[s.node[e]] += s.share[e] * grain_volume[p];
  return out;
}

std::vector<double> liquid_fraction(std::span<const double> solid, double node_volume, double eps_min) {
  std::vector<double> out(solid.size());
  for (std::size_t i = 0; i < solid.size(); ++i) out[i] = std::max(eps_min, 1.0 - solid[i] / node_volume);
  return out;
}

std::vector<double> liquid_fraction(std::span<const double> solid, std::span<const double> volume, double eps_min) {
  std::vector<double> out(solid.size());
  for (std::size_t i = 0; i < solid.size(); ++i) out[i] = std::max(eps_min, 1.0 - solid[i] / volume[i]);
  return out;
}

std::vector<double> at_grains(const GrainShares& s, std::span<const double> node_field) {
  std::vector<double> out(s.start.empty() ? 0 : s.start.size() - 1, 0.0);
  for (std::size_t p = 0; p < out.size(); ++p)
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) out[p] += s.share[e] * node_field[s.node[e]];
  return out;
}

void spread_reaction(const GrainShares& s, std::span<const V3<double>> grain_force, double node_volume,
                     std::span<V3<double>> node_force_density) {
  std::fill(node_force_density.begin(), node_force_density.end(), V3<double>{0.0, 0.0, 0.0});
  const double inv = 1.0 / node_volume;
  for (std::size_t p = 0; p + 1 < s.start.size(); ++p)
    for (std::uint32_t e = s.start[p]; e < s.start[p + 1]; ++e) {
      V3<double>& f = node_force_density[s.node[e]];
      f = f + (-s.share[e] * inv) * grain_force[p];
    }
}

}  // namespace gf
