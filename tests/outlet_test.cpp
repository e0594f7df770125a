// The outlet of a continuous scene (systems/flow/outlet.hpp) on a grains table fed by hand
// (systems/flow/feed.hpp): grains in the outlet region queued once and recorded with their entry and
// exit times, then gone from the table; grains present from the start recorded as not fed.
#include "systems/flow/outlet.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace {

// 1 g/s of 1 mm grains into a 20 mm box above the origin, in events 10 ms apart.
gf::FeedSpec feed() {
  gf::FeedSpec f;
  f.region = gf::Region::box({0.0, 0.0, 0.0}, {0.02, 0.02, 0.02});
  f.mass_rate = 5e-3;
  const double r = 0.5e-3, m = 2500.0 * 4.0 / 3.0 * std::numbers::pi * r * r * r;
  f.species = {{1, r, m, 1.0 / (0.4 * m * r * r), 1.0}};
  f.interval = 0.01;
  return f;
}

}  // namespace

TEST_CASE("outlet: grains in the region are queued once, recorded with their residence, then gone", "[outlet]") {
  const gf::FeedSpec f = feed();
  gf::FeedState s = gf::start_feed(f);
  gf::ResidenceLog log;
  gf::Grains g;
  gf::feed_events(g, f, s, log, 0.0);
  g.apply_pending();
  const std::size_t fed = g.n_owned;
  // The outlet: the lower half of the feed box.
  gf::OutletSpec o{gf::Region::box({0.0, 0.0, 0.0}, {0.02, 0.01, 0.02}), 0.05};
  gf::OutletState os;
  std::size_t below = 0;
  double below_mass = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    if (g.pos.y[i] <= 0.01) ++below, below_mass += g.mass.m[i];
  REQUIRE(below > 0);
  const auto out = gf::outlet_pass(g, o, os, log, 0.3);
  CHECK(out.size() == below);
  CHECK(os.discharged_mass == Approx(below_mass).epsilon(1e-12));
  for (const gf::ExitRecord& r : out) {
    CHECK(r.entry == 0.0);
    CHECK(r.exit == 0.3);
  }
  // Not due again before the interval, and never twice for one queued grain.
  CHECK(gf::outlet_pass(g, o, os, log, 0.32).empty());
  CHECK(gf::outlet_pass(g, o, os, log, 0.35).empty());
  g.apply_pending();
  CHECK(g.n_owned == fed - below);
  // A grain present from the start leaves with no entry time.
  gf::Grains h;
  h.resize(1);
  h.pid.id[0] = 0;
  h.next_id = 1;
  h.pos.x[0] = h.pos.y[0] = h.pos.z[0] = 0.005;
  gf::OutletState hs;
  gf::ResidenceLog none;
  const auto one = gf::outlet_pass(h, o, hs, none, 1.0);
  REQUIRE(one.size() == 1);
  CHECK(std::isnan(one[0].entry));
}

TEST_CASE("outlet: a bad interval or region is refused", "[outlet]") {
  gf::Grains g;
  gf::OutletState os;
  gf::ResidenceLog log;
  CHECK_THROWS_AS(gf::outlet_pass(g, {gf::Region::box({0, 0, 0}, {1, 1, 1}), 0.0}, os, log, 0.0),
                  std::invalid_argument);
  CHECK_THROWS_AS(gf::outlet_pass(g, {gf::Region::box({0, 0, 0}, {-1, 1, 1}), 0.1}, os, log, 0.0),
                  std::invalid_argument);
}
