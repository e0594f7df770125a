// The continuous feed (systems/flow/feed.hpp) on a grains table driven by hand: fed mass against
// rate x time, no overlaps, the same grains from the same seed, a backlog when the region is full,
// each fed grain's entry time found by its id.
#include "systems/flow/feed.hpp"

#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>


namespace {

constexpr double kRho = 2500.0;

gf::FeedSpecies species(std::int32_t type, double r, double fraction) {
  const double m = kRho * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  return {type, r, m, 1.0 / (0.4 * m * r * r), fraction};
}

// 0.33 by mass of 1 mm grains (type 1), 0.67 of 0.8 mm ones (type 0), into a 20 mm box above the
// origin, 5 g/s in events 10 ms apart.
gf::FeedSpec two_species_feed() {
  gf::FeedSpec f;
  f.region = gf::Region::box({0.0, 0.0, 0.0}, {0.02, 0.02, 0.02});
  f.mass_rate = 5e-3;
  f.species = {species(0, 0.4e-3, 0.67), species(1, 0.5e-3, 0.33)};
  f.velocity = {0.0, -0.1, 0.0};
  f.interval = 0.01;
  f.seed = 7;
  return f;
}

// Every pair of the table's grains apart (touching allowed, to rounding).
bool no_overlaps(const gf::Grains& g) {
  for (std::size_t i = 0; i < g.n_owned; ++i)
    for (std::size_t j = i + 1; j < g.n_owned; ++j) {
      const double dx = g.pos.x[i] - g.pos.x[j], dy = g.pos.y[i] - g.pos.y[j], dz = g.pos.z[i] - g.pos.z[j];
      if (std::sqrt(dx * dx + dy * dy + dz * dz) < g.radius.r[i] + g.radius.r[j] - 1e-12) return false;
    }
  return true;
}

double species_mass(const gf::Grains& g, std::int32_t type) {
  double m = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    if (g.species.type[i] == type) m += g.mass.m[i];
  return m;
}

// `events` feed events from t = 0, the table updated after each as the neighbour-list rebuild would.
void feed_for(gf::Grains& g, const gf::FeedSpec& f, gf::FeedState& s, gf::ResidenceLog& log, int events) {
  for (int k = 0; k < events; ++k) {
    gf::feed_events(g, f, s, log, k * f.interval);
    g.apply_pending();
  }
}

}  // namespace

TEST_CASE("feed: the fed mass of each species follows rate x fraction x time to within one grain", "[feed]") {
  const gf::FeedSpec f = two_species_feed();
  gf::FeedState s = gf::start_feed(f);
  gf::ResidenceLog log;
  gf::Grains g;
  feed_for(g, f, s, log, 20);
  CHECK(s.events == 20);
  const double fed_time = 20 * f.interval;
  for (const gf::FeedSpecies& sp : f.species) {
    // The debt left over is less than one grain: what was fed lags the rate by at most that.
    const double want = f.mass_rate * sp.fraction * fed_time, got = species_mass(g, sp.type);
    INFO("type " << sp.type << ": fed " << got << " kg of " << want);
    CHECK(got <= want + 1e-15);
    CHECK(got > want - sp.mass);
  }
  CHECK(s.fed_grains == static_cast<std::int64_t>(g.n_owned));
  CHECK(s.fed_mass == Approx(species_mass(g, 0) + species_mass(g, 1)).epsilon(1e-12));
  CHECK(s.backlog() < f.species[0].mass + f.species[1].mass);
  // Wholly inside the region, apart from each other, with the feed's velocity and no spin.
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    CHECK(f.region.contains_sphere({g.pos.x[i], g.pos.y[i], g.pos.z[i]}, g.radius.r[i]));
    CHECK(g.vel.y[i] == -0.1);
    CHECK(g.omega.x[i] == 0.0);
  }
  CHECK(no_overlaps(g));
}

TEST_CASE("feed: the same seed places the same grains, several events due at once included", "[feed]") {
  const gf::FeedSpec f = two_species_feed();
  auto run = [&](double step) {
    gf::FeedState s = gf::start_feed(f);
    gf::ResidenceLog log;
    gf::Grains g;
    for (double t = 0.0; t < 0.2 - 1e-12; t += step) {
      gf::feed_events(g, f, s, log, t);
      g.apply_pending();
    }
    return g;
  };
  // Stepping by one interval, or by three at once (three events held in one call): the events are
  // the same, each drawing from its own seed, so the grains are too.
  const gf::Grains a = run(0.01), b = run(0.01);
  REQUIRE(a.n_owned > 50);
  CHECK(a.n_owned == b.n_owned);
  bool same = true;
  for (std::size_t i = 0; i < a.n_owned; ++i) same = same && a.pos.x[i] == b.pos.x[i] && a.pid.id[i] == b.pid.id[i];
  CHECK(same);
  gf::FeedSpec other = f;
  other.seed = 8;
  gf::FeedState s = gf::start_feed(other);
  gf::ResidenceLog log;
  gf::Grains c;
  gf::feed_events(c, other, s, log, 0.0);
  c.apply_pending();
  CHECK(c.pos.x[0] != a.pos.x[0]);
}

TEST_CASE("feed: a full region leaves a backlog and never an overlap", "[feed]") {
  // A 3 mm box takes a few 1 mm grains (1.3 mg each); 10 g/s owes 76 of them per 10 ms event.
  gf::FeedSpec f;
  f.region = gf::Region::box({0.0, 0.0, 0.0}, {0.003, 0.003, 0.003});
  f.mass_rate = 1e-2;
  f.species = {species(1, 0.5e-3, 1.0)};
  f.interval = 0.01;
  f.attempts = 100;
  gf::FeedState s = gf::start_feed(f);
  gf::ResidenceLog log;
  gf::Grains g;
  gf::feed_events(g, f, s, log, 0.0);
  g.apply_pending();
  const std::size_t first = g.n_owned;
  CHECK(first >= 1);
  CHECK(s.backlog() > 0.5 * f.mass_rate * f.interval);
  // The next event sees the grains already there (in the table now) and adds none over them.
  gf::feed_events(g, f, s, log, 0.01);
  g.apply_pending();
  CHECK(no_overlaps(g));
  CHECK(s.backlog() > s.fed_mass);
}

TEST_CASE("feed: each fed grain's entry time is found by its id, and batches go when empty", "[feed]") {
  const gf::FeedSpec f = two_species_feed();
  gf::FeedState s = gf::start_feed(f);
  gf::ResidenceLog log;
  gf::Grains g;
  g.resize(3);  // three grains present from the start: ids 0, 1, 2
  for (std::size_t i = 0; i < 3; ++i) g.pid.id[i] = static_cast<std::int64_t>(i);
  g.next_id = 3;
  gf::feed_events(g, f, s, log, 0.0);
  gf::feed_events(g, f, s, log, 0.01);
  g.apply_pending();
  REQUIRE(log.batches.size() == 2);
  CHECK(log.batches[0].first == 3);
  CHECK(log.batches[1].first == 3 + log.batches[0].count);
  CHECK_FALSE(log.entry(1, false).has_value());
  CHECK(log.entry(3, false) == 0.0);
  CHECK(log.entry(log.batches[1].first, false) == 0.01);
  // Leaving counts a grain out of its batch; the batch goes with its last grain.
  const std::int64_t n0 = log.batches[0].count;
  for (std::int64_t id = 3; id < 3 + n0; ++id) CHECK(log.entry(id, true) == 0.0);
  CHECK(log.batches.size() == 1);
  CHECK_FALSE(log.entry(3, false).has_value());
}

TEST_CASE("feed: bad specs are refused", "[feed]") {
  gf::FeedSpec f = two_species_feed();
  f.species[0].fraction = 0.5;  // sums to 0.83
  CHECK_THROWS_AS(gf::start_feed(f), std::invalid_argument);
  f = two_species_feed();
  f.interval = 0.0;
  CHECK_THROWS_AS(gf::start_feed(f), std::invalid_argument);
  f = two_species_feed();
  f.species.clear();
  CHECK_THROWS_AS(gf::start_feed(f), std::invalid_argument);
  f = two_species_feed();
  f.region = gf::Region::box({0.0, 0.0, 0.0}, {-1.0, 0.02, 0.02});
  CHECK_THROWS_AS(gf::start_feed(f), std::invalid_argument);
}

TEST_CASE("feed: grains of a size distribution each draw a diameter and cost their own mass", "[feed]") {
  // Type 0 log-normal (mean 0.8 mm, sd 0.15 mm, cut at 0.5 and 1.2 mm): the fed mass still follows rate x
  // time to within one of the largest grains, each grain's mass and inertia are those of its own
  // diameter, and the sizes spread over the range.
  gf::FeedSpec f = two_species_feed();
  const auto law = std::make_shared<const gf::SizeDistribution>(gf::SizeDistribution::lognormal(0.8e-3, 0.15e-3, 0.5e-3, 1.2e-3));
  f.species[0] = species(0, 0.5 * law->smallest(), 0.67);  // mass of the smallest grain
  f.species[0].radius = 0.5 * law->largest();
  f.species[0].size = law;
  f.species[0].density = kRho;
  gf::FeedState s = gf::start_feed(f);
  gf::ResidenceLog log;
  gf::Grains g;
  feed_for(g, f, s, log, 20);
  const double largest = kRho * std::numbers::pi / 6.0 * std::pow(law->largest(), 3);
  const double want = f.mass_rate * 0.67 * 20 * f.interval, got = species_mass(g, 0);
  CHECK(got <= want + 1e-15);
  CHECK(got > want - largest);
  double lo = 1.0, hi = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    if (g.species.type[i] != 0) continue;
    const double d = 2.0 * g.radius.r[i], m = kRho * std::numbers::pi / 6.0 * d * d * d;
    CHECK(g.mass.m[i] == Approx(m).epsilon(1e-14));
    CHECK(g.mass.inv_inertia[i] == Approx(1.0 / (0.1 * m * d * d)).epsilon(1e-14));
    lo = std::min(lo, d), hi = std::max(hi, d);
  }
  CHECK(lo >= law->smallest());
  CHECK(hi <= law->largest());
  CHECK(hi - lo > 0.3e-3);  // hundreds of draws spread over most of the 0.7 mm range
  CHECK(no_overlaps(g));
  CHECK(s.fed_mass == Approx(species_mass(g, 0) + species_mass(g, 1)).epsilon(1e-12));
}
