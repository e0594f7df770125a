#include "systems/analysis/metrics.hpp"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "systems/analysis/sample_cells.hpp"

namespace gf {

Energies kinetic_energy(const Grains& g) {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, g.n_owned, 2048), Energies{},
      [&](const tbb::blocked_range<std::size_t>& r, Energies e) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const double v2 = g.vel.x[i] * g.vel.x[i] + g.vel.y[i] * g.vel.y[i] + g.vel.z[i] * g.vel.z[i];
          e.translational += 0.5 * g.mass.m[i] * v2;
          // Grains that do not rotate (no spin columns, or a species with inv_inertia 0) have none.
          if (!g.spin || g.mass.inv_inertia[i] == 0.0) continue;
          const double w2 = g.omega.x[i] * g.omega.x[i] + g.omega.y[i] * g.omega.y[i] + g.omega.z[i] * g.omega.z[i];
          e.rotational += 0.5 * w2 / g.mass.inv_inertia[i];
        }
        return e;
      },
      [](Energies a, const Energies& b) {
        a.translational += b.translational;
        a.rotational += b.rotational;
        return a;
      });
}

double potential_energy(const Grains& g, double gx, double gy, double gz) {
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, g.n_owned, 2048), 0.0,
      [&](const tbb::blocked_range<std::size_t>& r, double s) {
        for (std::size_t i = r.begin(); i != r.end(); ++i)
          s -= g.mass.m[i] * (gx * g.pos.x[i] + gy * g.pos.y[i] + gz * g.pos.z[i]);
        return s;
      },
      [](double a, double b) { return a + b; });
}

ContactStats contact_stats(const Grains& g, const NeighborList& list, const Walls& walls) {
  ContactStats pairs = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, list.pairs(), 4096), ContactStats{},
      [&](const tbb::blocked_range<std::size_t>& r, ContactStats s) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          const std::uint32_t i = list.i[k], j = list.j[k];
          const double dx = g.pos.x[j] - g.pos.x[i], dy = g.pos.y[j] - g.pos.y[i], dz = g.pos.z[j] - g.pos.z[i];
          const double rs = g.radius.r[i] + g.radius.r[j];
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 < rs * rs) {
            ++s.pair_contacts;
            const double ratio = (rs - std::sqrt(d2)) / (2.0 * std::min(g.radius.r[i], g.radius.r[j]));
            s.max_overlap_ratio = std::max(s.max_overlap_ratio, ratio);
          }
        }
        return s;
      },
      [](ContactStats a, const ContactStats& b) {
        a.pair_contacts += b.pair_contacts;
        a.max_overlap_ratio = std::max(a.max_overlap_ratio, b.max_overlap_ratio);
        return a;
      });
  ContactStats rows = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, g.n_owned, 2048), ContactStats{},
      [&](const tbb::blocked_range<std::size_t>& r, ContactStats s) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) {
          const Vec3d p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
          if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || !std::isfinite(g.vel.x[i]) ||
              !std::isfinite(g.vel.y[i]) || !std::isfinite(g.vel.z[i]))
            s.finite = false;
          for (const Wall& w : walls.list) {
            Vec3d n;
            const double gap = wall_gap(w, p, n);
            if (gap < g.radius.r[i]) {
              ++s.wall_contacts;
              s.max_overlap_ratio = std::max(s.max_overlap_ratio, (g.radius.r[i] - gap) / (2.0 * g.radius.r[i]));
            }
          }
        }
        return s;
      },
      [](ContactStats a, const ContactStats& b) {
        a.wall_contacts += b.wall_contacts;
        a.max_overlap_ratio = std::max(a.max_overlap_ratio, b.max_overlap_ratio);
        a.finite = a.finite && b.finite;
        return a;
      });
  pairs.wall_contacts = rows.wall_contacts;
  pairs.finite = rows.finite;
  pairs.max_overlap_ratio = std::max(pairs.max_overlap_ratio, rows.max_overlap_ratio);
  return pairs;
}

double segregation_index(const Grains& g, std::int32_t type_a, double cell, int min_grains) {
  const CellBinning b = bin_cells(g, type_a, cell);
  const double p = b.fraction_a();
  if (p <= 0.0 || p >= 1.0) return 0.0;
  const CellSpread s = cell_spread(b, p, min_grains);
  if (s.cells == 0) return 0.0;
  return std::sqrt(s.variance) / std::sqrt(p * (1.0 - p));
}

void add_mesh_contacts(ContactStats& s, const Grains& g, const MeshWalls& walls, double t, bool rotation_enabled) {
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double r = g.radius.r[i];
    for (const MeshContactPoint& c : mesh_contacts_of(walls, {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, r, t, rotation_enabled))
      if (c.gap < r) {
        ++s.wall_contacts;
        s.max_overlap_ratio = std::max(s.max_overlap_ratio, (r - c.gap) / (2.0 * r));
      }
  }
}

}  // namespace gf
