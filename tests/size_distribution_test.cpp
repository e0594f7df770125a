// Size distributions (systems/fill/size_distribution.hpp): drawn samples against the laws' moments within
// their sampling error, the truncated laws' moments against their closed forms, and a discrete table by
// mass turned into fractions by number.
//
// Tolerances. The mean of N draws has a standard error sd/sqrt(N) and the mean of d^2 one of
// sqrt(var(d^2)/N); a check within 5 standard errors fails by chance with probability 6e-7 (and the
// draws are seeded, so a pass is reproducible). Simpson's rule over 4000 intervals is exact to 1e-10 here.
#include "systems/fill/size_distribution.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

using gf::SizeDistribution;

namespace {

double phi(double z) { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }
double pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

struct Sample {
  double m1 = 0, m2 = 0, lo = INFINITY, hi = 0;
};

Sample draw(const SizeDistribution& s, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Sample out;
  for (int i = 0; i < n; ++i) {
    const double d = s.draw(rng);
    out.m1 += d / n;
    out.m2 += d * d / n;
    out.lo = std::min(out.lo, d);
    out.hi = std::max(out.hi, d);
  }
  return out;
}

// The sample's first two moments within five standard errors of the law's, and every draw within the cut-offs.
void check_sample(const SizeDistribution& s, int n) {
  const Sample x = draw(s, n, 7);
  const double m1 = s.moment(1), m2 = s.moment(2), m4 = s.moment(4);
  const double se1 = std::sqrt((m2 - m1 * m1) / n), se2 = std::sqrt((m4 - m2 * m2) / n);
  CHECK(std::abs(x.m1 - m1) < 5.0 * se1);
  CHECK(std::abs(x.m2 - m2) < 5.0 * se2);
  CHECK(x.lo >= s.smallest());
  CHECK(x.hi <= s.largest());
}

}  // namespace

TEST_CASE("a fixed size is every grain's and draws nothing from the generator") {
  const SizeDistribution s = SizeDistribution::fixed(2e-3);
  std::mt19937_64 a(3), b(3);
  CHECK(s.draw(a) == 2e-3);
  CHECK(a() == b());
  CHECK(s.moment(3) == Approx(8e-9));
  CHECK(s.smallest() == 2e-3);
  CHECK(s.largest() == 2e-3);
}

TEST_CASE("a truncated normal's moments against the closed form, and a sample against them") {
  // Cut at mean - 1 sd and mean + 2 sd: E[d] = mu + sigma (pdf(a) - pdf(b)) / (Phi(b) - Phi(a)).
  const double mu = 2e-3, sd = 3e-4;
  const SizeDistribution s = SizeDistribution::normal(mu, sd, mu - sd, mu + 2 * sd);
  const double z = phi(2.0) - phi(-1.0);
  const double mean = mu + sd * (pdf(-1.0) - pdf(2.0)) / z;
  const double var = sd * sd * (1.0 + (-1.0 * pdf(-1.0) - 2.0 * pdf(2.0)) / z - std::pow((pdf(-1.0) - pdf(2.0)) / z, 2));
  CHECK(s.moment(1) == Approx(mean).epsilon(1e-10));
  CHECK(s.moment(2) - s.moment(1) * s.moment(1) == Approx(var).epsilon(1e-8));
  check_sample(s, 200000);
  // The default cut-offs are three standard deviations.
  CHECK(SizeDistribution::default_min(SizeDistribution::Kind::Normal, mu, sd) == Approx(mu - 3 * sd));
}

TEST_CASE("a log-normal's moments against the closed form of the truncated law, and a sample against them") {
  // ln d ~ N(mu, s^2) cut at [a, b] in standard units: E[d^k] = exp(k mu + k^2 s^2 / 2)
  // (Phi(b - k s) - Phi(a - k s)) / (Phi(b) - Phi(a)).
  const double mean = 1e-3, sd = 5e-4;
  const double sigma = std::sqrt(std::log1p(sd * sd / (mean * mean))), mu = std::log(mean) - 0.5 * sigma * sigma;
  const double lo = SizeDistribution::default_min(SizeDistribution::Kind::LogNormal, mean, sd);
  const double hi = SizeDistribution::default_max(SizeDistribution::Kind::LogNormal, mean, sd);
  CHECK(std::log(lo) == Approx(mu - 3 * sigma));
  CHECK(std::log(hi) == Approx(mu + 3 * sigma));
  const SizeDistribution s = SizeDistribution::lognormal(mean, sd, lo, hi);
  for (int k = 1; k <= 3; ++k) {
    const double closed = std::exp(k * mu + 0.5 * k * k * sigma * sigma) * (phi(3 - k * sigma) - phi(-3 - k * sigma)) /
                          (phi(3) - phi(-3));
    CHECK(s.moment(k) == Approx(closed).epsilon(1e-9));
  }
  // Three standard deviations keep 99.7 % of the law: the mean moves by less than 1 %.
  CHECK(s.moment(1) == Approx(mean).epsilon(0.01));
  check_sample(s, 200000);
}

TEST_CASE("a discrete distribution by number and by mass") {
  // By mass, equal shares of 1 mm and 2 mm grains are eight small grains to each large one.
  const SizeDistribution m = SizeDistribution::discrete({2e-3, 1e-3}, {50, 50}, true);
  REQUIRE(m.diameters.size() == 2);
  CHECK(m.diameters[0] == 1e-3);
  CHECK(m.cumulative[0] == Approx(8.0 / 9.0));
  CHECK(m.smallest() == 1e-3);
  CHECK(m.largest() == 2e-3);
  const SizeDistribution n = SizeDistribution::discrete({1e-3, 2e-3, 3e-3}, {0.2, 0.0, 0.8}, false);
  CHECK(n.diameters.size() == 2);  // a size with no share is never drawn
  CHECK(n.moment(1) == Approx(0.2e-3 + 0.8 * 3e-3));
  // The fraction of large draws within five binomial standard errors.
  std::mt19937_64 rng(11);
  const int draws = 100000;
  int large = 0;
  for (int i = 0; i < draws; ++i) large += n.draw(rng) == 3e-3;
  CHECK(std::abs(large / double(draws) - 0.8) < 5.0 * std::sqrt(0.8 * 0.2 / draws));
  check_sample(n, 100000);
}

TEST_CASE("distributions that cannot be drawn are refused") {
  CHECK_THROWS_AS(SizeDistribution::discrete({1e-3}, {0.0}, false), std::invalid_argument);
  CHECK_THROWS_AS(SizeDistribution::discrete({1e-3, 2e-3}, {1.0}, false), std::invalid_argument);
  CHECK_THROWS_AS(SizeDistribution::discrete({-1e-3}, {1.0}, false), std::invalid_argument);
  // Cut-offs twelve standard deviations out hold about 1e-33 of the law.
  CHECK_THROWS_AS(SizeDistribution::normal(1e-3, 1e-5, 1.12e-3, 1.2e-3), std::invalid_argument);
  CHECK_THROWS_AS(SizeDistribution::normal(1e-3, 1e-4, 1.1e-3, 1.0e-3), std::invalid_argument);
}
