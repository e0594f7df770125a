#include "systems/mps/neighbors.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/simd.hpp"

namespace gf {

void wrap_periodic(FluidNodes& f, const Periodicity& per) {
  if (per.axis < 0) return;
  ColumnD& c = per.axis == 0 ? f.x : per.axis == 1 ? f.y : f.z;
  const double L = per.period();
  for (std::size_t i = 0; i < f.size(); ++i) {
    double v = c[i];
    if (v < per.lo || v >= per.hi) {
      v -= L * std::floor((v - per.lo) / L);
      if (v >= per.hi) v = per.lo;  // round-off at the upper edge
      c[i] = v;
    }
  }
}

namespace {

struct Grid {
  double origin[3];
  double cell[3];
  std::int64_t dims[3];
  std::vector<std::uint32_t> cell_of, start, order;
  // The nodes' coordinates and kinds in cell order (order[s] is node s's row): a cell's candidates are read
  // from consecutive memory, whatever order the flow has left the rows in.
  std::vector<double> sx, sy, sz;
  std::vector<std::int32_t> skind;
};

void bin(const FluidNodes& f, double radius, const Periodicity& per, Grid& g) {
  const std::size_t n = f.size();
  const ColumnD* c[3] = {&f.x, &f.y, &f.z};
  std::size_t cells = 1;
  for (int a = 0; a < 3; ++a) {
    if (a == 2 && f.dim == 2) {
      g.origin[a] = 0;
      g.cell[a] = 1;
      g.dims[a] = 1;
      continue;
    }
    if (a == per.axis) {
      g.dims[a] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::floor(per.period() / radius)));
      g.origin[a] = per.lo;
      g.cell[a] = per.period() / g.dims[a];
    } else {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t i = 0; i < n; ++i) {
        const double v = (*c[a])[i];
        if (!std::isfinite(v))
          throw std::runtime_error("neighbour search: node " + std::to_string(i) + " has a non-finite position");
        lo = std::min(lo, v);
        hi = std::max(hi, v);
      }
      g.origin[a] = lo;
      g.cell[a] = radius;
      g.dims[a] = static_cast<std::int64_t>(std::floor((hi - lo) / radius)) + 1;
    }
    cells *= static_cast<std::size_t>(g.dims[a]);
  }
  // A node flung far away would make the grid huge: refuse loudly (the run's domain check catches it first).
  if (cells > std::max<std::size_t>(std::size_t(1) << 26, 64 * n))
    throw std::runtime_error("neighbour search: the nodes span " + std::to_string(cells) +
                             " cells; a particle has left the domain");
  g.cell_of.resize(n);
  g.start.assign(cells + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    std::int64_t id[3];
    for (int a = 0; a < 3; ++a) {
      id[a] = static_cast<std::int64_t>(std::floor(((*c[a])[i] - g.origin[a]) / g.cell[a]));
      id[a] = std::clamp<std::int64_t>(id[a], 0, g.dims[a] - 1);
    }
    const auto cid = static_cast<std::uint32_t>((id[2] * g.dims[1] + id[1]) * g.dims[0] + id[0]);
    g.cell_of[i] = cid;
    ++g.start[cid + 1];
  }
  for (std::size_t k = 0; k < cells; ++k) g.start[k + 1] += g.start[k];
  g.order.resize(n);
  std::vector<std::uint32_t> fill(g.start.begin(), g.start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) g.order[fill[g.cell_of[i]]++] = static_cast<std::uint32_t>(i);
  g.sx.resize(n);
  g.sy.resize(n);
  g.sz.resize(n);
  g.skind.resize(n);
  for (std::size_t s = 0; s < n; ++s) {
    const std::uint32_t i = g.order[s];
    g.sx[s] = f.x[i];
    g.sy[s] = f.y[i];
    g.sz[s] = f.z[i];
    g.skind[s] = f.kind[i];
  }
}

// Calls emit(j, image) for every neighbour of row i.
template <class Emit>
void scan_row(const FluidNodes& f, const Grid& g, double r2max, const Periodicity& per, std::size_t i, Emit&& emit) {
  const double p[3] = {f.x[i], f.y[i], f.z[i]};
  std::int64_t id[3];
  for (int a = 0; a < 3; ++a) id[a] = (g.cell_of[i] / (a == 0 ? 1 : a == 1 ? g.dims[0] : g.dims[0] * g.dims[1])) % g.dims[a];
  const bool dummy_row = f.kind[i] == kDummy;
  const double *sx = g.sx.data(), *sy = g.sy.data(), *sz = g.sz.data();
  const int rz = g.dims[2] > 1 ? 1 : 0;
  const double L = per.period();
  for (int oz = -rz; oz <= rz; ++oz)
    for (int oy = -1; oy <= 1; ++oy)
      for (int ox = -1; ox <= 1; ++ox) {
        const int off[3] = {ox, oy, oz};
        std::int64_t cc[3];
        int image = 0;
        bool skip = false;
        for (int a = 0; a < 3; ++a) {
          cc[a] = id[a] + off[a];
          if (a == per.axis) {
            if (g.dims[a] < 3 && off[a] != 0) {
              skip = true;  // fewer than 3 cells: the load check forbids it, never double-count
              break;
            }
            if (cc[a] < 0) {
              cc[a] += g.dims[a];
              image = -1;
            } else if (cc[a] >= g.dims[a]) {
              cc[a] -= g.dims[a];
              image = 1;
            }
          } else if (cc[a] < 0 || cc[a] >= g.dims[a]) {
            skip = true;
            break;
          }
        }
        if (skip) continue;
        const std::size_t cid = static_cast<std::size_t>((cc[2] * g.dims[1] + cc[1]) * g.dims[0] + cc[0]);
        double add[3] = {0, 0, 0};  // the image's period (adding 0 is exact: the same sums as without it)
        if (image != 0) add[per.axis] = image * L;
        // Candidates kLanes at a time from the cell's start (the batches do not depend on the thread count), those
        // within the radius emitted in cell order, then the cell's last few one by one.
        auto take = [&](std::uint32_t s) {
          if (g.order[s] != i && (!dummy_row || g.skind[s] == kWall)) emit(g.order[s], image);
        };
        const std::uint32_t end = g.start[cid + 1];
        std::uint32_t s = g.start[cid];
        const BatchD px(p[0]), py(p[1]), pz(p[2]), ax(add[0]), ay(add[1]), az(add[2]), r2(r2max);
        for (; s + kLanes <= end; s += kLanes) {
          const BatchD dx = (BatchD::load_unaligned(sx + s) - px) + ax, dy = (BatchD::load_unaligned(sy + s) - py) + ay,
                       dz = (BatchD::load_unaligned(sz + s) - pz) + az;
          for (std::uint32_t bits = lane_bits(dx * dx + dy * dy + dz * dz < r2); bits != 0; bits &= bits - 1)
            take(s + static_cast<std::uint32_t>(std::countr_zero(bits)));
        }
        for (; s < end; ++s) {
          const double dx = (sx[s] - p[0]) + add[0], dy = (sy[s] - p[1]) + add[1], dz = (sz[s] - p[2]) + add[2];
          if (dx * dx + dy * dy + dz * dz < r2max) take(s);
        }
      }
}

}  // namespace

bool neighbors_stale(const FluidNodes& f, const NeighborPairs& nb, double skin, double dt) {
  if (nb.x0.size() != f.size()) return true;
  // The fluid's mean displacement since the build and its mean velocity: the common drift.
  double drift[3] = {0, 0, 0}, mean_u[3] = {0, 0, 0}, fluid = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] != kFluid) continue;
    drift[0] += f.x[i] - nb.x0[i], drift[1] += f.y[i] - nb.y0[i], drift[2] += f.z[i] - nb.z0[i];
    mean_u[0] += f.u[i], mean_u[1] += f.v[i], mean_u[2] += f.w[i];
    fluid += 1;
  }
  if (fluid == 0) return false;
  for (int a = 0; a < 3; ++a) drift[a] /= fluid, mean_u[a] /= fluid;
  const auto norm = [](double x, double y, double z) { return std::sqrt(x * x + y * y + z * z); };
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] != kFluid) continue;
    const double dx = f.x[i] - nb.x0[i], dy = f.y[i] - nb.y0[i], dz = f.z[i] - nb.z0[i];
    const double own = norm(dx, dy, dz) + 2.0 * dt * norm(f.u[i], f.v[i], f.w[i]);
    const double apart = norm(dx - drift[0], dy - drift[1], dz - drift[2]) +
                         2.0 * dt * norm(f.u[i] - mean_u[0], f.v[i] - mean_u[1], f.w[i] - mean_u[2]);
    if (!(own <= skin && apart <= 0.5 * skin)) return true;
  }
  return false;
}

void build_neighbors(const FluidNodes& f, double radius, const Periodicity& per, NeighborPairs& out) {
  const std::size_t n = f.size();
  out.x0.assign(f.x.begin(), f.x.end());
  out.y0.assign(f.y.begin(), f.y.end());
  out.z0.assign(f.z.begin(), f.z.end());
  ++out.builds;
  Grid g;
  bin(f, radius, per, g);
  const double r2 = radius * radius;
  out.start.assign(n + 1, 0);
  out.periodic = per;
  out.radius = radius;
  // One scan: each block of rows gathers its pairs into its own buffer (sized from the last list's pairs per
  // row), counting each row's; the blocks are then copied into place in row order, instead of scanning the
  // cells twice, once to count and once to fill.
  constexpr std::size_t kRowsPerBlock = 256;
  const std::size_t blocks = (n + kRowsPerBlock - 1) / kRowsPerBlock;
  const std::size_t per_row = n > 0 && out.j.size() > 0 ? out.j.size() / n + 8 : 64;
  std::vector<std::vector<std::uint32_t>> found(blocks);
  std::vector<std::vector<std::int8_t>> images(blocks);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const std::size_t lo = b * kRowsPerBlock, hi = std::min(n, lo + kRowsPerBlock);
    std::vector<std::uint32_t>& js = found[b];
    std::vector<std::int8_t>& ims = images[b];
    js.reserve(per_row * (hi - lo));
    ims.reserve(per_row * (hi - lo));
    for (std::size_t i = lo; i < hi; ++i) {
      const std::size_t before = js.size();
      scan_row(f, g, r2, per, i, [&](std::uint32_t q, int image) {
        js.push_back(q);
        ims.push_back(static_cast<std::int8_t>(image));
      });
      out.start[i + 1] = static_cast<std::uint32_t>(js.size() - before);
    }
  });
  for (std::size_t i = 0; i < n; ++i) out.start[i + 1] += out.start[i];
  const std::size_t m = out.start[n];
  out.j.resize(m);
  out.image.resize(m);
  out.w.assign(m, 0.0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t b) {
    const std::size_t at = out.start[b * kRowsPerBlock];
    std::copy(found[b].begin(), found[b].end(), out.j.begin() + static_cast<std::ptrdiff_t>(at));
    std::copy(images[b].begin(), images[b].end(), out.image.begin() + static_cast<std::ptrdiff_t>(at));
  });
}

}  // namespace gf
