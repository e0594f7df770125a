#include "systems/fill/size_distribution.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace gf {

namespace {

double normal_cdf(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

// The z in [lo, hi] with normal_cdf(z) = p, by bisection to the last bit (monotone, so it cannot fail).
double normal_quantile(double p, double lo, double hi) {
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    (normal_cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double lognormal_sigma(double mean, double sd) { return std::sqrt(std::log1p(sd * sd / (mean * mean))); }

}  // namespace

double sphere_mass(double density, double diameter) {
  const double r = 0.5 * diameter;
  return density * 4.0 / 3.0 * std::numbers::pi * r * r * r;
}

SizeDistribution SizeDistribution::fixed(double d) {
  SizeDistribution s;
  s.kind = Kind::Fixed;
  s.value = s.min = s.max = d;
  return s;
}

SizeDistribution SizeDistribution::discrete(std::vector<double> diameters, std::vector<double> fractions, bool by_mass) {
  if (diameters.empty() || diameters.size() != fractions.size())
    throw std::invalid_argument("give as many fractions as diameters, at least one");
  std::vector<std::pair<double, double>> rows;
  for (std::size_t k = 0; k < diameters.size(); ++k) {
    const double d = diameters[k], f = fractions[k];
    if (!(d > 0.0) || !std::isfinite(d)) throw std::invalid_argument("diameter " + std::to_string(d) + " is not > 0");
    if (!(f >= 0.0) || !std::isfinite(f)) throw std::invalid_argument("fraction " + std::to_string(f) + " is not >= 0");
    if (f > 0.0) rows.emplace_back(d, by_mass ? f / (d * d * d) : f);
  }
  if (rows.empty()) throw std::invalid_argument("the fractions sum to 0");
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  SizeDistribution s;
  s.kind = Kind::Discrete;
  double sum = 0.0;
  for (const auto& r : rows) sum += r.second;
  double acc = 0.0;
  for (const auto& [d, f] : rows) {
    acc += f;
    s.diameters.push_back(d);
    s.cumulative.push_back(acc / sum);
  }
  s.cumulative.back() = 1.0;
  s.min = s.diameters.front();
  s.max = s.diameters.back();
  return s;
}

void SizeDistribution::set_normal_law(double mu_y, double sigma_y) {
  mu = mu_y;
  sigma = sigma_y;
  const auto z = [&](double d) { return ((kind == Kind::LogNormal ? std::log(d) : d) - mu) / sigma; };
  if (!(min < max)) throw std::invalid_argument("the cut-offs must have min < max");
  p_lo = normal_cdf(z(min));
  p_hi = normal_cdf(z(max));
  if (!(p_hi - p_lo >= 1e-9)) throw std::invalid_argument("the cut-offs hold less than 1e-9 of the distribution");
}

namespace {

// A normal or log-normal law of the diameter's mean and sd, cut at [min, max].
SizeDistribution continuous(SizeDistribution::Kind kind, double mean, double sd, double min, double max) {
  SizeDistribution s;
  s.kind = kind;
  s.mean = mean;
  s.sd = sd;
  s.min = min;
  s.max = max;
  if (!(min > 0.0)) throw std::invalid_argument("the smallest diameter must be > 0");
  if (kind == SizeDistribution::Kind::Normal) {
    s.set_normal_law(mean, sd);
  } else {
    const double sigma = lognormal_sigma(mean, sd);
    s.set_normal_law(std::log(mean) - 0.5 * sigma * sigma, sigma);
  }
  return s;
}

}  // namespace

SizeDistribution SizeDistribution::normal(double mean, double sd, double min, double max) {
  return continuous(Kind::Normal, mean, sd, min, max);
}

SizeDistribution SizeDistribution::lognormal(double mean, double sd, double min, double max) {
  return continuous(Kind::LogNormal, mean, sd, min, max);
}

double SizeDistribution::default_min(Kind kind, double mean, double sd) {
  if (kind != Kind::LogNormal) return mean - 3.0 * sd;
  const double sigma = lognormal_sigma(mean, sd);
  return std::exp(std::log(mean) - 0.5 * sigma * sigma - 3.0 * sigma);
}

double SizeDistribution::default_max(Kind kind, double mean, double sd) {
  if (kind != Kind::LogNormal) return mean + 3.0 * sd;
  const double sigma = lognormal_sigma(mean, sd);
  return std::exp(std::log(mean) - 0.5 * sigma * sigma + 3.0 * sigma);
}

double SizeDistribution::to_diameter(double y) const {
  const double d = kind == Kind::LogNormal ? std::exp(y) : y;
  return std::clamp(d, min, max);
}

double SizeDistribution::moment(int k) const {
  switch (kind) {
    case Kind::Fixed:
      return std::pow(value, k);
    case Kind::Discrete: {
      double m = 0.0, below = 0.0;
      for (std::size_t i = 0; i < diameters.size(); ++i) {
        m += (cumulative[i] - below) * std::pow(diameters[i], k);
        below = cumulative[i];
      }
      return m;
    }
    default:
      break;
  }
  // Simpson's rule in the normal variable z over the cut-offs: the integrand is smooth, and 4000
  // intervals over at most a few dozen standard deviations resolve it to about 1e-12.
  const double za = (kind == Kind::LogNormal ? std::log(min) : min), zb = (kind == Kind::LogNormal ? std::log(max) : max);
  const double a = (za - mu) / sigma, b = (zb - mu) / sigma;
  constexpr int n = 4000;
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i <= n; ++i) {
    const double z = a + i * h;
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * std::pow(to_diameter(mu + sigma * z), k) * normal_pdf(z);
  }
  return sum * h / 3.0 / (p_hi - p_lo);
}

double SizeDistribution::draw(std::mt19937_64& rng) const {
  if (kind == Kind::Fixed) return value;
  const double u = portable_uniform01(rng);
  if (kind == Kind::Discrete) {
    const auto it = std::upper_bound(cumulative.begin(), cumulative.end(), u);
    return diameters[static_cast<std::size_t>(std::min<std::ptrdiff_t>(it - cumulative.begin(),
                                                                       static_cast<std::ptrdiff_t>(diameters.size()) - 1))];
  }
  const double za = (kind == Kind::LogNormal ? std::log(min) : min), zb = (kind == Kind::LogNormal ? std::log(max) : max);
  const double z = normal_quantile(p_lo + u * (p_hi - p_lo), (za - mu) / sigma, (zb - mu) / sigma);
  return to_diameter(mu + sigma * z);
}

std::string SizeDistribution::describe(std::string (*length)(double)) const {
  switch (kind) {
    case Kind::Fixed:
      return length(value);
    case Kind::Discrete:
      if (diameters.size() == 1) return length(min);
      return std::to_string(diameters.size()) + " sizes, " + length(min) + " to " + length(max);
    case Kind::Normal:
    case Kind::LogNormal:
      return std::string(kind == Kind::Normal ? "normal" : "log-normal") + ", mean " + length(mean) + ", sd " +
             length(sd) + ", " + length(min) + " to " + length(max);
  }
  return length(value);
}

}  // namespace gf
