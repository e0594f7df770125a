#include "systems/mps/boundaries.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

Periodicity LiquidGeometry::periodicity() const {
  Periodicity p;
  if (kind == Kind::Channel || kind == Kind::Pipe) {
    p.axis = 0;
    p.lo = lo[0];
    p.hi = hi[0];
  }
  return p;
}

bool LiquidGeometry::interior(double x, double y, double z) const {
  if (kind == Kind::Pipe) {
    const double dy = y - center[1], dz = z - center[2];
    return x >= lo[0] && x < hi[0] && dy * dy + dz * dz < radius * radius;
  }
  const double p[3] = {x, y, z};
  for (int a = 0; a < dim; ++a) {
    if (p[a] < lo[a]) return false;
    if (p[a] > hi[a] && !(kind == Kind::Tank && a == 1)) return false;
  }
  return true;
}

void LiquidGeometry::bounds(double l0, std::array<double, 3>& blo, std::array<double, 3>& bhi) const {
  const double pad = layers * l0;
  for (int a = 0; a < 3; ++a) {
    if (a >= dim) {
      blo[a] = bhi[a] = 0;
      continue;
    }
    if (kind == Kind::Pipe && a > 0) {
      blo[a] = center[a] - radius - pad;
      bhi[a] = center[a] + radius + pad;
    } else {
      const bool periodic = (kind == Kind::Channel || kind == Kind::Pipe) && a == 0;
      blo[a] = periodic ? lo[a] : lo[a] - pad;
      bhi[a] = periodic ? hi[a] : hi[a] + pad;
    }
  }
}

namespace {

// Layer index of a lattice node outside the fluid region: 1 for the wall layer, 2.. for dummy layers, 0 inside.
int layer_of(const LiquidGeometry& g, double l0, const double p[3]) {
  double d = 0;
  if (g.kind == LiquidGeometry::Kind::Pipe) {
    const double dy = p[1] - g.center[1], dz = p[2] - g.center[2];
    const double r = std::sqrt(dy * dy + dz * dz);
    if (r < g.radius - 1e-9 * l0) return 0;  // nodes on the radius (to round-off) are wall nodes
    return std::max(1, static_cast<int>(std::ceil((r - g.radius) / l0 - 1e-9)));
  } else {
    for (int a = 0; a < g.dim; ++a) {
      if (a == 0 && g.kind == LiquidGeometry::Kind::Channel) continue;
      double o = std::max(g.lo[a] - p[a], 0.0);
      if (!(g.kind == LiquidGeometry::Kind::Tank && a == 1)) o = std::max(o, p[a] - g.hi[a]);
      d = std::max(d, o);
    }
  }
  if (d <= 0) return 0;
  return static_cast<int>(std::ceil(d / l0 - 1e-9));
}

}  // namespace

void generate_nodes(const LiquidGeometry& g, const std::vector<FluidBlock>& blocks, double l0, FluidNodes& f) {
  f.dim = g.dim;
  std::array<double, 3> blo, bhi;
  g.bounds(l0, blo, bhi);
  // Lattice origin: the inner faces (box: nodes sit half a spacing from each face) or, for the pipe, a node on
  // the axis.
  std::array<double, 3> origin = g.lo;
  if (g.kind == LiquidGeometry::Kind::Pipe) origin = {g.lo[0], g.center[1] - 0.5 * l0, g.center[2] - 0.5 * l0};
  std::array<long, 3> i0{0, 0, 0}, i1{0, 0, 0};
  for (int a = 0; a < g.dim; ++a) {
    i0[a] = static_cast<long>(std::floor((blo[a] - origin[a]) / l0 - 1e-9));
    i1[a] = static_cast<long>(std::ceil((bhi[a] - origin[a]) / l0 + 1e-9));
  }
  struct Node {
    NodeKind k;
    double x, y, z;
    std::array<double, 3> v{};
  };
  std::vector<Node> fluid, solid;
  for (long k = i0[2]; k <= i1[2]; ++k)
    for (long j = i0[1]; j <= i1[1]; ++j)
      for (long i = i0[0]; i <= i1[0]; ++i) {
        double p[3] = {origin[0] + (i + 0.5) * l0, origin[1] + (j + 0.5) * l0,
                       g.dim == 3 ? origin[2] + (k + 0.5) * l0 : 0.0};
        bool inside_bounds = true;
        for (int a = 0; a < g.dim; ++a) {
          const bool periodic = a == 0 && (g.kind == LiquidGeometry::Kind::Channel || g.kind == LiquidGeometry::Kind::Pipe);
          if (periodic ? (p[a] < blo[a] || p[a] >= bhi[a]) : (p[a] < blo[a] || p[a] > bhi[a])) inside_bounds = false;
        }
        if (!inside_bounds) continue;
        if (g.kind == LiquidGeometry::Kind::Tank && p[1] > g.hi[1]) continue;
        const int layer = layer_of(g, l0, p);
        if (layer == 0) {
          for (const FluidBlock& b : blocks) {
            bool in = true;
            for (int a = 0; a < g.dim; ++a) in = in && p[a] >= b.lo[a] && p[a] < b.hi[a];
            if (in) {
              fluid.push_back({kFluid, p[0], p[1], p[2], b.velocity});
              break;
            }
          }
        } else if (layer <= g.layers) {
          solid.push_back({layer == 1 ? kWall : kDummy, p[0], p[1], p[2]});
        }
      }
  const std::size_t base = f.size();
  f.resize(base + fluid.size() + solid.size());
  std::size_t r = base;
  for (const auto* list : {&fluid, &solid})
    for (const Node& nd : *list) {
      f.x[r] = nd.x;
      f.y[r] = nd.y;
      f.z[r] = nd.z;
      f.u[r] = nd.v[0];
      f.v[r] = nd.v[1];
      f.w[r] = nd.v[2];
      f.kind[r] = nd.k;
      ++r;
    }
}

void extrapolate_dummy_pressure(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp) {
  const double ax = lp.gravity[0] + lp.body_force[0], ay = lp.gravity[1] + lp.body_force[1],
               az = lp.gravity[2] + lp.body_force[2];
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] != kDummy) continue;
      double sw = 0, sp = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
        const double w = nb.w[q];
        if (w == 0) continue;  // the list holds only wall neighbours for dummy rows
        double dx, dy, dz;
        nb.rel(f, i, q, dx, dy, dz);  // r_w - r_d
        sw += w;
        sp += w * (f.p[nb.j[q]] - lp.rho * (ax * dx + ay * dy + az * dz));
      }
      f.p[i] = sw > 0 ? sp / sw : 0.0;
    }
  });
}

}  // namespace gf
