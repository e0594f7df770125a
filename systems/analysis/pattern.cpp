#include "systems/analysis/pattern.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "systems/analysis/free_surface.hpp"

namespace gf {

namespace {

constexpr int kRadialBins = 256;

// Volumes per angular bin of one ring of the section (the rim band, or a ring about a radius).
struct Ring {
  explicit Ring(int bins = 0) : large(bins, 0.0), total(bins, 0.0), large_count(bins, 0) {}
  void add(int b, double vol, bool is_large) {
    total[b] += vol;
    if (is_large) large[b] += vol, ++large_count[b], ++large_grains;
  }
  std::vector<double> large, total;
  std::vector<int> large_count;
  std::size_t large_grains = 0;
};

// Small-grain lobes along a ring's arc of bed (see the header's method), with what the decision reads.
struct RingLobes {
  bool defined = false;  // the ring holds an arc of bed of at least 8 bins
  int lobes = 0, small_bins = 0, len = 0;
  double arc = 0, noise = 0, contrast = 0, mean = 0, window_bins = 1;
};

// Probability that a Poisson count of mean lambda is at most n, its terms taken in log space (no
// underflow of exp(-lambda) however large lambda is).
double poisson_at_most(int n, double lambda) {
  if (!(lambda > 0)) return 1.0;
  const double log_lambda = std::log(lambda);
  double top = -INFINITY;
  for (int k = 0; k <= n; ++k) top = std::max(top, k * log_lambda - std::lgamma(k + 1.0));
  double sum = 0;
  for (int k = 0; k <= n; ++k) sum += std::exp(k * log_lambda - std::lgamma(k + 1.0) - top);
  return std::min(1.0, std::exp(top - lambda + std::log(sum)));
}

// alpha > 0: a run also needs its large grains improbably few for the ring's mixture, a Poisson
// probability below alpha per independent window of the arc (see the header).
RingLobes ring_lobes(const Ring& ring, double p, const PatternSettings& s, double alpha) {
  RingLobes out;
  const int nb = static_cast<int>(ring.total.size());
  const std::vector<double>& total = ring.total;
  const std::vector<double>& large = ring.large;
  // The bed's arc: the longest circular run of bins whose 5-bin window holds at least 0.3 of a
  // typical filled window (single 2-degree bins hold only a few large grains: too noisy alone).
  std::vector<double> window(nb, 0.0);
  for (int b = 0; b < nb; ++b)
    for (int j = -2; j <= 2; ++j) window[b] += total[(b + j + nb) % nb];
  std::vector<double> filled;
  for (double t : window)
    if (t > 0) filled.push_back(t);
  if (filled.empty()) return out;
  std::nth_element(filled.begin(), filled.begin() + filled.size() / 2, filled.end());
  const double cut = 0.3 * filled[filled.size() / 2];
  int best_start = 0, best_len = 0;
  for (int start = 0; start < nb; ++start) {
    if (window[start] < cut || window[(start + nb - 1) % nb] >= cut) continue;  // runs start after an empty bin
    int len = 0;
    while (len < nb && window[(start + len) % nb] >= cut) ++len;
    if (len > best_len) best_len = len, best_start = start;
  }
  if (best_len == 0 && window[0] >= cut) best_len = nb;  // the band is filled all round
  const int trim = static_cast<int>(std::lround(s.trim_bins));
  const int len = best_len == nb ? nb : best_len - 2 * trim;
  const int first = best_len == nb ? 0 : best_start + trim;
  if (len < 8) return out;
  out.defined = true;
  out.len = len;
  out.arc = 2 * std::numbers::pi * len / nb;

  // Smoothed, normalised profile along the arc (volumes smoothed, then divided).
  const double norm = std::sqrt(p * (1 - p));
  // Noise of s in a random mixture: the large volume in a smoothing window is a count of N large
  // grains, relative spread 1/sqrt(N) (small grains are many more), so s spreads by
  // sqrt(p (1 - p) / N). The window holds the large grains of 2 sqrt(pi) sigma bins.
  double large_in_arc = 0;
  for (int k = 0; k < len; ++k) large_in_arc += ring.large_count[(first + k) % nb];
  out.window_bins = std::max(1.0, 2.0 * std::sqrt(std::numbers::pi) * s.smooth_bins);
  out.noise = std::sqrt(p * (1 - p) / std::max(1.0, large_in_arc * out.window_bins / len));
  const int reach = static_cast<int>(std::ceil(3 * s.smooth_bins));
  std::vector<double> prof(len);
  double sum_abs = 0, sum = 0;
  for (int k = 0; k < len; ++k) {
    double wl = 0, wt = 0;
    for (int j = std::max(0, k - reach); j <= std::min(len - 1, k + reach); ++j) {
      const double d = (j - k) / std::max(s.smooth_bins, 1e-9);
      const double w = s.smooth_bins > 0 ? std::exp(-0.5 * d * d) : (j == k ? 1.0 : 0.0);
      const int b = (first + j) % nb;
      wl += w * large[b];
      wt += w * total[b];
    }
    prof[k] = wt > 0 ? (wl / wt - p) / norm : 0.0;
    sum_abs += std::abs(prof[k]);
    sum += prof[k];
  }
  out.contrast = sum_abs / len;
  out.mean = sum / len;

  // Lobes about the profile's mean, so unequal lobe and wedge volumes (p away from 1/2) or label
  // noise (which pulls both levels towards p) do not shift the count; a run needs a swing of at
  // least 2 h and of 0.4 of the profile's range, so noise within one level does not make one.
  const auto [lo_it, hi_it] = std::minmax_element(prof.begin(), prof.end());
  const double mid = out.mean, half = std::max({s.hysteresis, 0.2 * (*hi_it - *lo_it), 2.5 * out.noise});
  // Large grains per unit of volume over the arc: a run's expected count in a mixture.
  double vol_in_arc = 0;
  for (int k = 0; k < len; ++k) vol_in_arc += total[(first + k) % nb];
  const double rate = large_in_arc / vol_in_arc, per_window = alpha * out.window_bins / len;
  int run_large = 0;
  double run_volume = 0;
  auto significant = [&] { return alpha <= 0 || poisson_at_most(run_large, rate * run_volume) < per_window; };
  bool in_small = false;
  for (int k = 0; k < len; ++k) {
    const double v = prof[k];
    if (!in_small && v < mid - half) {
      in_small = true, run_large = 0, run_volume = 0;
    } else if (in_small && v > mid + half) {
      in_small = false;
      out.lobes += significant();
    }
    // The run's own bins: those below the mean (the hysteresis carries it on into the next wedge).
    if (in_small && v < mid) run_large += ring.large_count[(first + k) % nb], run_volume += total[(first + k) % nb];
    out.small_bins += in_small;
  }
  if (in_small) out.lobes += significant();
  return out;
}

}  // namespace

Pattern classify_pattern(const PatternGrains& g, const DrumSection& drum, const PatternSettings& s) {
  const std::size_t n = g.x.size();
  if (g.y.size() != n || g.z.size() != n || g.r.size() != n || g.type.size() != n)
    throw std::invalid_argument("pattern: grain columns differ in length");
  if (!(drum.radius > 0) || s.bins < 16 || !(s.band_share > 0) || !(s.smooth_bins >= 0) || s.trim_bins < 0 ||
      !(s.hysteresis > 0) || !(s.min_contrast >= 0) || !(s.ring_alpha > 0 && s.ring_alpha < 1) || s.ring_trim_bins < 0)
    throw std::invalid_argument("pattern: settings out of range");

  Pattern out;
  const double R = drum.radius;
  // The free surface (its own pass), then volumes (r^3; the 4/3 pi cancels in every ratio) and the
  // radial histogram.
  const FreeSurface top = free_surface({g.x, g.y, g.z, g.r, {}, {}, {}}, drum);
  out.surface_angle = top.angle;
  out.surface_level = top.level;
  std::array<double, kRadialBins> radial{};
  double v_all = 0, v_large = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = drum.u(g.x[i], g.y[i], g.z[i]), v = drum.v(g.x[i], g.y[i], g.z[i]);
    const double vol = g.r[i] * g.r[i] * g.r[i];
    v_all += vol;
    if (g.type[i] == s.large_type) v_large += vol;
    // Bins are found in double and clamped before the conversion: a grain far outside the drum (a
    // corrupt state) must land in the last bin, not overflow the int.
    const int rb = static_cast<int>(std::min<double>(kRadialBins - 1, std::sqrt(u * u + v * v) / R * kRadialBins));
    radial[rb] += vol;
  }
  if (!(v_large > 0) || !(v_large < v_all)) return out;
  const double p = v_large / v_all;
  out.large_fraction = p;

  // Band: outermost radial bins holding band_share of the large volume.
  double acc = 0;
  int rb_in = kRadialBins;
  while (rb_in > 0 && acc < s.band_share * v_large) acc += radial[--rb_in];
  const double r_in = R * rb_in / kRadialBins;
  out.band_inner = r_in;

  // Pass 2: the composition against the angle about the axis, in the band and in each ring.
  const int nb = s.bins;
  const double r_in2 = r_in * r_in;
  Ring band(nb);
  std::array<Ring, kRingRadii.size()> rings;
  rings.fill(Ring(nb));
  for (std::size_t i = 0; i < n; ++i) {
    const double u = drum.u(g.x[i], g.y[i], g.z[i]), v = drum.v(g.x[i], g.y[i], g.z[i]);
    const double rr = u * u + v * v, rho = std::sqrt(rr) / R;
    const bool in_band = rr >= r_in2;
    bool in_ring = false;
    for (const double rk : kRingRadii) in_ring = in_ring || std::abs(rho - rk) <= kRingHalfWidth;
    if (!in_band && !in_ring) continue;
    const double th = std::atan2(v, u) + std::numbers::pi;  // [0, 2 pi]
    const int b = static_cast<int>(std::min<double>(nb - 1, th / (2 * std::numbers::pi) * nb));
    const double vol = g.r[i] * g.r[i] * g.r[i];
    const bool large = g.type[i] == s.large_type;
    if (in_band) band.add(b, vol, large);
    for (std::size_t k = 0; k < rings.size(); ++k)
      if (std::abs(rho - kRingRadii[k]) <= kRingHalfWidth) rings[k].add(b, vol, large);
  }
  for (std::size_t k = 0; k < rings.size(); ++k) {
    PatternSettings rs = s;
    rs.trim_bins = s.ring_trim_bins;
    const RingLobes l = rings[k].large_grains < s.min_large_in_band ? RingLobes{} : ring_lobes(rings[k], p, rs, s.ring_alpha);
    out.ring_lobes[k] = l.defined ? l.lobes : -1;
  }

  if (band.large_grains < s.min_large_in_band) return out;
  const RingLobes l = ring_lobes(band, p, s, 0.0);
  if (!l.defined) return out;
  out.arc = l.arc;
  out.noise = l.noise;
  out.contrast = l.contrast;
  const int lobes = l.lobes, small_bins = l.small_bins, len = l.len;
  const double mean = l.mean, window_bins = l.window_bins;

  // Petals need lobes standing out of the noise; a moon needs a band richer in large grains than
  // the bed, by more than h and by 3 standard errors of the mean over the arc's independent windows.
  const double mean_error = out.noise / std::sqrt(std::max(1.0, len / window_bins));
  if (lobes >= 2 && out.contrast >= std::max(s.min_contrast, 2.0 * out.noise)) {
    out.kind = PatternKind::Petals;
    out.petals = lobes;
  } else if ((lobes == 0 || (lobes == 1 && 3 * small_bins <= len)) && mean > std::max(s.hysteresis, 3.0 * mean_error)) {
    out.kind = PatternKind::Moon;
  }
  return out;
}

}  // namespace gf
