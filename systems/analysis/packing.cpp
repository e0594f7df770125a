#include "systems/analysis/packing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <vector>

#include <Eigen/Geometry>

#include "systems/bodies/mass_properties.hpp"
#include "systems/bodies/member_core.hpp"

namespace gf {

namespace {

// The voxel grid of a box: dims voxels per axis, each of edge `edge` (the box split evenly, so an edge
// is h rounded to fit), solid[i + dims0 (j + dims1 k)] = 1 where the voxel's centre lies in a moving
// body's member.
struct VoxelGrid {
  std::array<double, 3> lo{}, edge{};
  std::array<std::size_t, 3> dims{};
  std::vector<std::uint8_t> solid;
  std::size_t index(std::size_t i, std::size_t j, std::size_t k) const { return i + dims[0] * (j + dims[1] * k); }
};

VoxelGrid voxelize(const Bodies& bodies, const Members& members, const std::array<double, 3>& lo,
                   const std::array<double, 3>& hi, double h) {
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("packing: the voxel edge must be positive");
  VoxelGrid g;
  g.lo = lo;
  double total = 1.0;
  for (int d = 0; d < 3; ++d) {
    if (!(hi[d] > lo[d])) throw std::invalid_argument("packing: the box needs hi > lo on every axis");
    g.dims[d] = static_cast<std::size_t>(std::max(1.0, std::round((hi[d] - lo[d]) / h)));
    total *= static_cast<double>(g.dims[d]);
  }
  if (total > static_cast<double>(1u << 30)) throw std::invalid_argument("packing: more than 2^30 voxels: a larger h");
  for (int d = 0; d < 3; ++d) g.edge[d] = (hi[d] - lo[d]) / static_cast<double>(g.dims[d]);
  const auto& dims = g.dims;
  const auto& edge = g.edge;
  g.solid.assign(dims[0] * dims[1] * dims[2], 0);
  for (std::size_t m = 0; m < members.n; ++m) {
    const std::uint32_t b = members.body.row[m];
    if (!bodies.moving(b)) continue;
    const Eigen::Quaterniond q(bodies.q.w[b], bodies.q.x[b], bodies.q.y[b], bodies.q.z[b]);
    const Eigen::Vector3d x(bodies.pos.x[b], bodies.pos.y[b], bodies.pos.z[b]);
    const Eigen::Matrix3d to_body = q.normalized().toRotationMatrix().transpose();
    const std::uint32_t first = members.core.first[m], count = members.core.count[m];
    const CoreView view{static_cast<CoreKind>(members.core.kind[m]),
                        std::span<const double>(members.vertices.x.data() + first, count),
                        std::span<const double>(members.vertices.y.data() + first, count),
                        std::span<const double>(members.vertices.z.data() + first, count)};
    const std::unique_ptr<CoreSolid> core = core_solid(view);
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
          std::uint8_t& cell = g.solid[g.index(i, j, k)];
          if (cell) continue;
          const Eigen::Vector3d p(lo[0] + (static_cast<double>(i) + 0.5) * edge[0],
                                  lo[1] + (static_cast<double>(j) + 0.5) * edge[1],
                                  lo[2] + (static_cast<double>(k) + 0.5) * edge[2]);
          if (core->dilated_contains(to_body * (p - x), r)) cell = 1;
        }
  }
  return g;
}

}  // namespace

PackingFraction packing_fraction(const Bodies& bodies, const Members& members, const std::array<double, 3>& lo,
                                 const std::array<double, 3>& hi, double h) {
  const VoxelGrid g = voxelize(bodies, members, lo, hi, h);
  PackingFraction out;
  out.voxels = g.solid.size();
  out.solid = static_cast<std::size_t>(std::count(g.solid.begin(), g.solid.end(), std::uint8_t{1}));
  out.fraction = static_cast<double>(out.solid) / static_cast<double>(out.voxels);
  return out;
}

namespace {

// The box holding the moving bodies' members' bounding spheres; false when no body moves.
bool moving_bounds(const Bodies& bodies, const Members& members, std::array<double, 3>& lo, std::array<double, 3>& hi) {
  lo.fill(std::numeric_limits<double>::infinity());
  hi.fill(-std::numeric_limits<double>::infinity());
  for (std::size_t m = 0; m < members.n; ++m) {
    if (!bodies.moving(members.body.row[m])) continue;
    const double c[3] = {members.centre.x[m], members.centre.y[m], members.centre.z[m]};
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d] - members.bound.radius[m]);
      hi[d] = std::max(hi[d], c[d] + members.bound.radius[m]);
    }
  }
  return lo[0] < hi[0];
}

// The first and last solid voxel index along each axis; false when none is solid.
bool solid_span(const VoxelGrid& g, std::array<std::size_t, 3>& first, std::array<std::size_t, 3>& last) {
  first = g.dims, last = {};
  bool any = false;
  for (std::size_t k = 0; k < g.dims[2]; ++k)
    for (std::size_t j = 0; j < g.dims[1]; ++j)
      for (std::size_t i = 0; i < g.dims[0]; ++i)
        if (g.solid[g.index(i, j, k)]) {
          any = true;
          const std::size_t at[3] = {i, j, k};
          for (int d = 0; d < 3; ++d) {
            first[d] = std::min(first[d], at[d]);
            last[d] = std::max(last[d], at[d]);
          }
        }
  return any;
}

// The bed's voxels by layer from the floor: the axes across (a, b) and up, the bed's and the
// interior's index spans, and what the columns hold.
struct BedColumns {
  int a = 0, b = 0, up = 0, up_sign = 1;
  std::array<std::size_t, 3> first{}, last{}, in_first{}, in_last{};
  std::vector<std::size_t> solid_in, solid_all;  // solid voxels per layer: in the interior, in the bed
  double top_sum = 0;                            // m, the interior's filled columns' heights summed
  std::size_t columns = 0;                       // the interior's filled columns
};

// Layer l is the voxel index first + l (up_sign +1) or last - l.
void count_columns(const VoxelGrid& g, BedColumns& c) {
  const std::size_t n_layers = c.last[c.up] - c.first[c.up] + 1;
  const auto voxel_at = [&](std::size_t ia, std::size_t ib, std::size_t layer) {
    std::size_t at[3]{};
    at[c.a] = ia;
    at[c.b] = ib;
    at[c.up] = c.up_sign > 0 ? c.first[c.up] + layer : c.last[c.up] - layer;
    return g.solid[g.index(at[0], at[1], at[2])];
  };
  c.solid_in.assign(n_layers, 0);
  c.solid_all.assign(n_layers, 0);
  for (std::size_t ib = c.first[c.b]; ib <= c.last[c.b]; ++ib)
    for (std::size_t ia = c.first[c.a]; ia <= c.last[c.a]; ++ia) {
      const bool inside = ia >= c.in_first[c.a] && ia <= c.in_last[c.a] && ib >= c.in_first[c.b] && ib <= c.in_last[c.b];
      std::size_t top = 0;
      bool filled = false;
      for (std::size_t l = 0; l < n_layers; ++l)
        if (voxel_at(ia, ib, l)) {
          ++c.solid_all[l];
          if (inside) ++c.solid_in[l];
          top = l;
          filled = true;
        }
      if (inside && filled) {
        c.top_sum += static_cast<double>(top + 1) * g.edge[c.up];
        ++c.columns;
      }
    }
}

// The layers' fractions, the whole bed's and the interior's (between `margin` above the floor and
// `margin` below the surface), and the interior's box. Sets out.valid, or out.reason.
void finish_layers(const VoxelGrid& g, const BedColumns& c, double margin, BedPacking& out) {
  const int a = c.a, b = c.b, up = c.up;
  const double e = g.edge[up];
  const std::size_t cols_in = (c.in_last[a] - c.in_first[a] + 1) * (c.in_last[b] - c.in_first[b] + 1);
  const std::size_t cols_all = (c.last[a] - c.first[a] + 1) * (c.last[b] - c.first[b] + 1);
  const double depth = c.top_sum / static_cast<double>(c.columns);
  out.surface = out.floor + c.up_sign * depth;
  const std::size_t n_layers = c.solid_in.size();
  std::size_t l_first = n_layers, l_last = 0;
  for (std::size_t l = 0; l < n_layers; ++l) {
    const double centre = (static_cast<double>(l) + 0.5) * e;
    out.layers.push_back({centre, static_cast<double>(c.solid_in[l]) / static_cast<double>(cols_in),
                          static_cast<double>(c.solid_all[l]) / static_cast<double>(cols_all)});
    if (centre < depth) {
      out.whole.voxels += cols_all;
      out.whole.solid += c.solid_all[l];
    }
    if (centre >= margin && centre <= depth - margin) {
      l_first = std::min(l_first, l);
      l_last = std::max(l_last, l);
      out.interior.voxels += cols_in;
      out.interior.solid += c.solid_in[l];
    }
  }
  if (out.interior.voxels == 0) {
    out.reason = "the bed is shallower than two margins";
    return;
  }
  out.interior.fraction = static_cast<double>(out.interior.solid) / static_cast<double>(out.interior.voxels);
  out.whole.fraction = static_cast<double>(out.whole.solid) / static_cast<double>(out.whole.voxels);
  for (const int d : {a, b}) {
    out.lo[d] = g.lo[d] + static_cast<double>(c.in_first[d]) * g.edge[d];
    out.hi[d] = g.lo[d] + static_cast<double>(c.in_last[d] + 1) * g.edge[d];
  }
  const double z0 = out.floor + c.up_sign * static_cast<double>(l_first) * e;
  const double z1 = out.floor + c.up_sign * static_cast<double>(l_last + 1) * e;
  out.lo[up] = std::min(z0, z1);
  out.hi[up] = std::max(z0, z1);
  out.valid = true;
}

}  // namespace

BedPacking bed_packing(const Bodies& bodies, const Members& members, int up, int up_sign, double margin, double h) {
  if (up < 0 || up > 2 || (up_sign != 1 && up_sign != -1))
    throw std::invalid_argument("packing: the up axis is 0, 1 or 2 and its sign +1 or -1");
  if (!(margin >= 0.0) || !std::isfinite(margin)) throw std::invalid_argument("packing: the margin must be >= 0");
  BedPacking out;
  out.margin = margin;
  std::array<double, 3> lo{}, hi{};
  if (!moving_bounds(bodies, members, lo, hi)) {
    out.reason = "no moving bodies";
    return out;
  }
  if (!(h > 0.0) || !std::isfinite(h)) throw std::invalid_argument("packing: the voxel edge must be positive");
  // Voxels on a grid of pitch h from the origin, so that beds sampled alike share their voxels.
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::floor(lo[d] / h) * h;
    hi[d] = std::max(lo[d] + h, std::ceil(hi[d] / h) * h);
  }
  const VoxelGrid g = voxelize(bodies, members, lo, hi, h);
  out.voxel = g.edge;
  BedColumns c;
  c.up = up, c.up_sign = up_sign, c.a = (up + 1) % 3, c.b = (up + 2) % 3;
  if (!solid_span(g, c.first, c.last)) {
    out.reason = "no voxel centre lies in a body: a smaller voxel edge";
    return out;
  }
  for (int d = 0; d < 3; ++d) {
    out.bed_lo[d] = g.lo[d] + static_cast<double>(c.first[d]) * g.edge[d];
    out.bed_hi[d] = g.lo[d] + static_cast<double>(c.last[d] + 1) * g.edge[d];
  }
  // The interior's columns: voxels whose centres lie at least `margin` inside the bed's lateral extent.
  for (const int d : {c.a, c.b}) {
    const auto inset = static_cast<std::size_t>(std::max(0.0, std::ceil(margin / g.edge[d] - 0.5)));
    if (c.last[d] < c.first[d] + 2 * inset) {
      out.reason = "the bed is narrower than two margins";
      return out;
    }
    c.in_first[d] = c.first[d] + inset;
    c.in_last[d] = c.last[d] - inset;
  }
  out.floor = up_sign > 0 ? out.bed_lo[up] : out.bed_hi[up];
  count_columns(g, c);
  if (c.columns == 0) {
    out.reason = "no grain in the interior's columns";
    return out;
  }
  finish_layers(g, c, margin, out);
  return out;
}

}  // namespace gf
