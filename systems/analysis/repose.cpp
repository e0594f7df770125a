#include "systems/analysis/repose.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "systems/analysis/line_fit.hpp"

namespace gf {

namespace {

double length(const V3<double>& v) { return std::sqrt(dot(v, v)); }

constexpr std::size_t kMaxColumns = 1u << 20;  // a profile finer than this is a mistake in `column`

void check(const ReposeGrains& g, const V3<double>& up, const ReposeSettings& s) {
  const std::size_t n = g.x.size();
  if (g.y.size() != n || g.z.size() != n || g.r.size() != n)
    throw std::invalid_argument("repose: grain columns differ in length");
  if (!(length(up) > 0.0) || !std::isfinite(length(up))) throw std::invalid_argument("repose: 'up' must be a non-zero vector");
  if (!(s.column > 0.0) || !std::isfinite(s.column) || s.rank < 1 || !(s.lower >= 0.0) || !(s.lower < s.upper) ||
      !(s.upper <= 1.0) || s.min_columns < 2)
    throw std::invalid_argument("repose: settings out of range (column > 0, rank >= 1, 0 <= lower < upper <= 1, "
                                "min_columns >= 2)");
}

// The surface of each column: the rank-th highest top, NaN where a column holds fewer grains.
struct Profile {
  double s0 = 0.0, width = 0.0;
  std::vector<double> height;
  double centre(std::size_t c) const { return s0 + (static_cast<double>(c) + 0.5) * width; }
};

Profile profile(const std::vector<double>& s, const std::vector<double>& top, const ReposeSettings& set) {
  Profile p;
  p.width = set.column;
  if (s.empty()) return p;
  const auto [lo, hi] = std::minmax_element(s.begin(), s.end());
  p.s0 = *lo;
  const double span = (*hi - *lo) / set.column;
  if (!(span < static_cast<double>(kMaxColumns)))
    throw std::invalid_argument("repose: the grains span more than 2^20 columns: give a wider column");
  const std::size_t cols = static_cast<std::size_t>(span) + 1, k = static_cast<std::size_t>(set.rank);
  // Per column its k highest tops, in decreasing order.
  std::vector<double> best(cols * k, -INFINITY);
  std::vector<std::size_t> count(cols, 0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    const std::size_t c = std::min(cols - 1, static_cast<std::size_t>((s[i] - p.s0) / set.column));
    ++count[c];
    double* b = &best[c * k];
    if (!(top[i] > b[k - 1])) continue;
    std::size_t j = k - 1;
    for (; j > 0 && top[i] > b[j - 1]; --j) b[j] = b[j - 1];
    b[j] = top[i];
  }
  p.height.assign(cols, std::numeric_limits<double>::quiet_NaN());
  for (std::size_t c = 0; c < cols; ++c)
    if (count[c] >= k) p.height[c] = best[c * k + k - 1];
  return p;
}

// The flank over columns [from, to) of the profile, whose extreme surface is `extreme`.
ReposeFlank fit_flank(const Profile& p, std::size_t from, std::size_t to, double extreme, bool crater,
                      const ReposeSettings& set) {
  ReposeFlank f;
  double foot = crater ? -INFINITY : INFINITY;
  for (std::size_t c = from; c < to; ++c) {
    const double h = p.height[c];
    if (std::isnan(h)) continue;
    foot = crater ? std::max(foot, h) : std::min(foot, h);
  }
  const double range = extreme - foot;
  if (!std::isfinite(range) || range == 0.0) return f;
  LineFit fit;
  for (std::size_t c = from; c < to; ++c) {
    const double h = p.height[c];
    if (std::isnan(h)) continue;
    const double frac = (h - foot) / range;
    if (frac < set.lower || frac > set.upper) continue;
    const double x = p.centre(c);
    if (f.columns == 0) f.s_from = x;
    f.s_to = x;
    ++f.columns;
    fit.add(x, h);
  }
  if (f.columns < static_cast<std::size_t>(set.min_columns) || std::isnan(fit.slope())) return f;
  f.slope = fit.slope();
  f.angle = std::atan(std::abs(f.slope));
  return f;
}

Repose measure(const std::vector<double>& s, const std::vector<double>& top, const ReposeSettings& set, bool crater,
               bool two_flanks) {
  Repose out;
  const Profile p = profile(s, top, set);
  std::size_t ext = p.height.size();
  for (std::size_t c = 0; c < p.height.size(); ++c) {
    const double h = p.height[c];
    if (std::isnan(h)) continue;
    if (ext == p.height.size() || (crater ? h < p.height[ext] : h > p.height[ext])) ext = c;
  }
  if (ext == p.height.size()) return out;
  out.extreme_height = p.height[ext];
  out.extreme_s = p.centre(ext);
  if (two_flanks) {
    out.first = fit_flank(p, 0, ext, out.extreme_height, crater, set);
    out.second = fit_flank(p, ext + 1, p.height.size(), out.extreme_height, crater, set);
  } else {
    out.first = fit_flank(p, ext + 1, p.height.size(), out.extreme_height, crater, set);
  }
  return out;
}

}  // namespace

Repose repose_radial(const ReposeGrains& g, const V3<double>& centre, const V3<double>& up, const ReposeSettings& set) {
  check(g, up, set);
  const V3<double> u = (1.0 / length(up)) * up;
  const std::size_t n = g.x.size();
  std::vector<double> s(n), top(n);
  for (std::size_t i = 0; i < n; ++i) {
    const V3<double> d{g.x[i] - centre.x, g.y[i] - centre.y, g.z[i] - centre.z};
    const double h = dot(d, u);
    s[i] = std::sqrt(std::max(0.0, dot(d, d) - h * h));
    top[i] = h + g.r[i];
  }
  return measure(s, top, set, false, false);
}

Repose repose_planar(const ReposeGrains& g, const V3<double>& across, const V3<double>& up, const ReposeSettings& set,
                     bool crater) {
  check(g, up, set);
  const V3<double> u = (1.0 / length(up)) * up;
  const V3<double> a = across - dot(across, u) * u;
  if (!(length(a) > 1e-12 * length(across)) || !std::isfinite(length(a)))
    throw std::invalid_argument("repose: 'across' must have a horizontal part");
  const V3<double> h_dir = (1.0 / length(a)) * a;
  const std::size_t n = g.x.size();
  std::vector<double> s(n), top(n);
  for (std::size_t i = 0; i < n; ++i) {
    const V3<double> p{g.x[i], g.y[i], g.z[i]};
    s[i] = dot(p, h_dir);
    top[i] = dot(p, u) + g.r[i];
  }
  return measure(s, top, set, crater, true);
}

}  // namespace gf
