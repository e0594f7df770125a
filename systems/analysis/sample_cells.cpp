#include "systems/analysis/sample_cells.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>
#include <utility>

namespace gf {

namespace {

// 21 bits per axis: cells two million apart share a key, far past any scene's extent in cells.
std::uint64_t cell_key(double x, double y, double z, double inv) {
  const auto cx = static_cast<std::int64_t>(std::floor(x * inv)) & 0x1fffff;
  const auto cy = static_cast<std::int64_t>(std::floor(y * inv)) & 0x1fffff;
  const auto cz = static_cast<std::int64_t>(std::floor(z * inv)) & 0x1fffff;
  return (static_cast<std::uint64_t>(cx) << 42) | (static_cast<std::uint64_t>(cy) << 21) |
         static_cast<std::uint64_t>(cz);
}

}  // namespace

CellBinning bin_cells(const Grains& g, std::int32_t type_a, double cell) {
  CellBinning b;
  std::unordered_map<std::uint64_t, CellComposition> cells;
  cells.reserve(g.n_owned / 4 + 1);
  const double inv = 1.0 / cell;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double r = g.radius.r[i];
    const double vol = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    CellComposition& c = cells[cell_key(g.pos.x[i], g.pos.y[i], g.pos.z[i], inv)];
    c.volume += vol;
    ++c.grains;
    b.volume += vol;
    b.volume_sq += vol * vol;
    if (g.species.type[i] == type_a) {
      c.volume_a += vol;
      b.volume_a += vol;
      b.volume_sq_a += vol * vol;
    }
  }
  std::vector<std::pair<std::uint64_t, CellComposition>> sorted(cells.begin(), cells.end());
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& c) { return a.first < c.first; });
  b.cells.reserve(sorted.size());
  for (const auto& kc : sorted) b.cells.push_back(kc.second);
  return b;
}

CellSpread cell_spread(const CellBinning& b, double p, int min_grains) {
  CellSpread s;
  double sum = 0.0;
  for (const CellComposition& c : b.cells) {
    if (c.grains < min_grains || !(c.volume > 0.0)) continue;
    const double f = c.volume_a / c.volume;
    sum += c.volume * (f - p) * (f - p);
    s.volume += c.volume;
    s.grains += c.grains;
    ++s.cells;
  }
  s.variance = s.volume > 0.0 ? sum / s.volume : 0.0;
  return s;
}

}  // namespace gf
