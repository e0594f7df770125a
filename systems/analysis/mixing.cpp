#include "systems/analysis/mixing.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "systems/analysis/sample_cells.hpp"

namespace gf {

namespace {

// sr^2 of mixing.hpp: p (1 - p) [(1 - p) w_A + p w_B] / V for 0 < p < 1.
double random_variance(const CellBinning& b, double p, double cell_volume) {
  const double w_a = b.volume_sq_a / b.volume_a;
  const double w_b = (b.volume_sq - b.volume_sq_a) / (b.volume - b.volume_a);
  return p * (1.0 - p) * ((1.0 - p) * w_a + p * w_b) / cell_volume;
}

double grain_volume(double r) { return 4.0 / 3.0 * std::numbers::pi * r * r * r; }

// Each owned grain's section coordinates and volume, and the bed's centroid in the section.
struct Section {
  std::vector<double> rho2, vol;  // squared distance from the centroid (m^2), volume (m^3)
  double u = 0.0, v = 0.0, volume = 0.0;
};

Section section_of(const Grains& g, const DrumSection& drum) {
  const std::size_t n = g.n_owned;
  Section s;
  std::vector<double> u(n), v(n);
  s.vol.resize(n);
  double su = 0.0, sv = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    u[i] = drum.u(g.pos.x[i], g.pos.y[i], g.pos.z[i]);
    v[i] = drum.v(g.pos.x[i], g.pos.y[i], g.pos.z[i]);
    s.vol[i] = grain_volume(g.radius.r[i]);
    su += s.vol[i] * u[i];
    sv += s.vol[i] * v[i];
    s.volume += s.vol[i];
  }
  if (!(s.volume > 0.0)) return s;
  s.u = su / s.volume;
  s.v = sv / s.volume;
  s.rho2.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.rho2[i] = (u[i] - s.u) * (u[i] - s.u) + (v[i] - s.v) * (v[i] - s.v);
  return s;
}

// Rows in order of distance from the centroid, ties by id, so the split does not depend on row order.
std::vector<std::size_t> by_distance(const Grains& g, const Section& s) {
  std::vector<std::size_t> order(s.rho2.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return s.rho2[a] != s.rho2[b] ? s.rho2[a] < s.rho2[b] : g.pid.id[a] < g.pid.id[b];
  });
  return order;
}

}  // namespace

LaceyIndex lacey_index(const Grains& g, std::int32_t type_a, double cell, int min_grains) {
  if (!(cell > 0.0) || !std::isfinite(cell) || min_grains < 1)
    throw std::invalid_argument("lacey_index: the cell edge must be positive and finite, min_grains at least 1");
  LaceyIndex out;
  out.cell = cell;
  const CellBinning b = bin_cells(g, type_a, cell);
  const double p = b.fraction_a();
  const CellSpread s = cell_spread(b, p, min_grains);
  out.fraction_a = p;
  out.segregated = p * (1.0 - p);
  out.variance = s.variance;
  out.cells = s.cells;
  if (s.cells == 0 || p <= 0.0 || p >= 1.0) return out;
  out.grains_per_cell = static_cast<double>(s.grains) / static_cast<double>(s.cells);
  out.random = random_variance(b, p, s.volume / static_cast<double>(s.cells));
  if (out.random < out.segregated) out.index = (out.segregated - out.variance) / (out.segregated - out.random);
  return out;
}

RadialSegregation radial_segregation(const Grains& g, std::int32_t type_a, const DrumSection& drum) {
  RadialSegregation out;
  const Section s = section_of(g, drum);
  if (!(s.volume > 0.0)) return out;
  out.centre_u = s.u;
  out.centre_v = s.v;
  double core = 0.0, core_a = 0.0, periphery = 0.0, periphery_a = 0.0;
  for (const std::size_t i : by_distance(g, s)) {
    const bool a = g.species.type[i] == type_a;
    if (core < 0.5 * s.volume) {
      core += s.vol[i];
      core_a += a ? s.vol[i] : 0.0;
      out.split_radius = std::sqrt(s.rho2[i]);
    } else {
      periphery += s.vol[i];
      periphery_a += a ? s.vol[i] : 0.0;
    }
  }
  out.core_fraction = core_a / core;
  if (!(periphery > 0.0)) return out;
  out.periphery_fraction = periphery_a / periphery;
  const double sum = out.periphery_fraction + out.core_fraction;
  if (sum > 0.0) out.index = (out.periphery_fraction - out.core_fraction) / sum;
  return out;
}

}  // namespace gf
