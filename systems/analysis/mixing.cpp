#include "systems/analysis/mixing.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <utility>
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

// The volume fraction of A in the half of the bed (by solid volume) with the smallest keys, and in
// the other half. Rows are taken in order of key, ties by id, so the split does not depend on row
// order; the first half ends with the row at which its volume first reaches half the bed's.
struct HalfSplit {
  double first = std::numeric_limits<double>::quiet_NaN();   // phi of the first half (smallest keys)
  double second = std::numeric_limits<double>::quiet_NaN();  // phi of the rest; NaN when empty
  double last_key = 0.0;                                     // the key of the first half's last row
};

HalfSplit split_half(const Grains& g, std::int32_t type_a, const std::vector<double>& key,
                     const std::vector<double>& vol, double total) {
  std::vector<std::size_t> order(key.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return key[a] != key[b] ? key[a] < key[b] : g.pid.id[a] < g.pid.id[b];
  });
  double first = 0.0, first_a = 0.0, second = 0.0, second_a = 0.0;
  HalfSplit out;
  for (const std::size_t i : order) {
    const double a = g.species.type[i] == type_a ? vol[i] : 0.0;
    if (first < 0.5 * total) {
      first += vol[i];
      first_a += a;
      out.last_key = key[i];
    } else {
      second += vol[i];
      second_a += a;
    }
  }
  if (first > 0.0) out.first = first_a / first;
  if (second > 0.0) out.second = second_a / second;
  return out;
}

// (phi_b - phi_a) / (phi_b + phi_a); NaN when undefined.
double contrast_index(double phi_a, double phi_b) {
  const double sum = phi_a + phi_b;
  return sum > 0.0 ? (phi_b - phi_a) / sum : std::numeric_limits<double>::quiet_NaN();
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
  const HalfSplit h = split_half(g, type_a, s.rho2, s.vol, s.volume);
  out.split_radius = std::sqrt(h.last_key);
  out.core_fraction = h.first;
  out.periphery_fraction = h.second;
  if (std::isfinite(h.second)) out.index = contrast_index(h.first, h.second);
  return out;
}

DepthSegregation depth_segregation(const Grains& g, std::int32_t type_a, const DrumSection& drum,
                                   double surface_angle, double surface_level) {
  DepthSegregation out;
  if (!std::isfinite(surface_angle) || !std::isfinite(surface_level)) return out;
  const std::size_t n = g.n_owned;
  std::vector<double> neg_depth(n), vol(n);
  const double c = std::cos(surface_angle), sn = std::sin(surface_angle);
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = drum.u(g.pos.x[i], g.pos.y[i], g.pos.z[i]), v = drum.v(g.pos.x[i], g.pos.y[i], g.pos.z[i]);
    // Below the line v = level + u tan(a) by (level + u tan(a) - v) cos(a) = level cos(a) + u sin(a) - v cos(a).
    neg_depth[i] = -(surface_level * c + u * sn - v * c);
    vol[i] = grain_volume(g.radius.r[i]);
    total += vol[i];
  }
  if (!(total > 0.0)) return out;
  // Smallest keys first: the deepest grains, then up to the surface.
  const HalfSplit h = split_half(g, type_a, neg_depth, vol, total);
  out.split_depth = -h.last_key;
  out.deep_fraction = h.first;
  out.shallow_fraction = h.second;
  if (std::isfinite(h.second)) out.index = contrast_index(h.second, h.first);
  return out;
}

LayerCells layer_cells(const Grains& g, std::int32_t type_a, const V3<double>& inlet, const V3<double>& axis,
                       double distance, double thickness, double cell) {
  const double len = std::sqrt(dot(axis, axis));
  if (!(len > 0.0) || !std::isfinite(len) || !(thickness > 0.0) || !std::isfinite(thickness) || !(cell > 0.0) ||
      !std::isfinite(cell) || !std::isfinite(distance))
    throw std::invalid_argument("layer_mixing: the axis must be a non-zero vector, thickness and cell positive and "
                                "finite");
  // An orthonormal frame (e1, e2) of the layer's plane.
  const V3<double> a = (1.0 / len) * axis;
  const V3<double> helper = std::abs(a.x) < 0.9 ? V3<double>{1, 0, 0} : V3<double>{0, 1, 0};
  V3<double> e1 = cross(a, helper);
  e1 = (1.0 / std::sqrt(dot(e1, e1))) * e1;
  const V3<double> e2 = cross(a, e1);
  LayerCells out;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const V3<double> d{g.pos.x[i] - inlet.x, g.pos.y[i] - inlet.y, g.pos.z[i] - inlet.z};
    if (!(std::abs(dot(d, a) - distance) <= 0.5 * thickness)) continue;
    const double v = grain_volume(g.radius.r[i]);
    const bool is_a = g.species.type[i] == type_a;
    const auto key = std::make_pair(static_cast<std::int64_t>(std::floor(dot(d, e1) / cell)),
                                    static_cast<std::int64_t>(std::floor(dot(d, e2) / cell)));
    CellComposition& c = out.cells[key];
    c.volume += v;
    c.volume_a += is_a ? v : 0.0;
    ++c.grains;
    out.volume += v;
    out.volume_sq += v * v;
    out.volume_a += is_a ? v : 0.0;
    out.volume_sq_a += is_a ? v * v : 0.0;
  }
  return out;
}

void LayerCells::add(const LayerCells& more) {
  for (const auto& [key, c] : more.cells) {
    CellComposition& to = cells[key];
    to.volume += c.volume;
    to.volume_a += c.volume_a;
    to.grains += c.grains;
  }
  volume += more.volume;
  volume_a += more.volume_a;
  volume_sq += more.volume_sq;
  volume_sq_a += more.volume_sq_a;
}

LayerMixing layer_quality(const LayerCells& cells, int min_grains) {
  if (min_grains < 1) throw std::invalid_argument("layer_quality: min_grains must be at least 1");
  CellBinning b;
  for (const auto& [key, c] : cells.cells) b.cells.push_back(c);
  b.volume = cells.volume;
  b.volume_a = cells.volume_a;
  b.volume_sq = cells.volume_sq;
  b.volume_sq_a = cells.volume_sq_a;
  LayerMixing out;
  // The mean over the counted cells only: the cells left out are left out of V as well.
  double counted = 0.0, counted_a = 0.0;
  for (const CellComposition& c : b.cells)
    if (c.grains >= min_grains) {
      counted += c.volume;
      counted_a += c.volume_a;
    }
  if (!(counted > 0.0)) return out;
  const double p = counted_a / counted;
  const CellSpread sp = cell_spread(b, p, min_grains);
  out.fraction_a = p;
  out.cells = sp.cells;
  out.grains = sp.grains;
  out.grains_per_cell = static_cast<double>(sp.grains) / static_cast<double>(sp.cells);
  if (!(p > 0.0)) return out;
  out.vc = std::sqrt(sp.variance) / p;
  if (p < 1.0 && b.volume_a > 0.0 && b.volume_a < b.volume) {
    const double s0 = p * (1.0 - p), sr = random_variance(b, p, sp.volume / static_cast<double>(sp.cells));
    if (sr < s0) out.lacey = (s0 - sp.variance) / (s0 - sr);
  }
  return out;
}

LayerMixing layer_mixing(const Grains& g, std::int32_t type_a, const V3<double>& inlet, const V3<double>& axis,
                         double distance, double thickness, double cell, int min_grains) {
  if (min_grains < 1) throw std::invalid_argument("layer_mixing: min_grains must be at least 1");
  return layer_quality(layer_cells(g, type_a, inlet, axis, distance, thickness, cell), min_grains);
}

}  // namespace gf
