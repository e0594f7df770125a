#include "systems/setup/flow_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "systems/setup/scene_fields.hpp"

namespace gf {

namespace {

double read_interval(const SceneNode& node, const DemScene& s, const FieldTable& fields) {
  const double dt = read_number(node, fields.field("interval"));
  if (dt < s.dt) node.fail("interval", "shorter than the time step", "use at least run.dt (" + short_number(s.dt) + " s)");
  return dt;
}

FeedSpec read_feed(const DemScene& s, const SceneNode& f, std::size_t index) {
  FeedSpec spec;
  spec.region = read_fill_region(f, s.gravity);
  spec.mass_rate = read_number(f, kFeedFields.field("mass_rate"));
  const SceneNode fr = f.table("fractions");
  double sum = 0.0;
  for (const std::string& name : fr.keys()) {
    const std::int32_t k = species_index(s, fr, name, name);
    const SpeciesSpec& sp = s.species[k];
    const double frac = fr.get_double(name, kFeedFields.field("fractions.<species>").range);
    spec.species.push_back({k, 0.5 * sp.largest(), sp.mass, sp.rotates ? 1.0 / sp.inertia : 0.0, frac});
    if (!sp.size.is_fixed()) {
      spec.species.back().size = std::make_shared<const SizeDistribution>(sp.size);
      spec.species.back().density = sp.density;
    }
    sum += frac;
  }
  if (spec.species.empty()) f.fail("fractions", "no species to feed", "e.g. fractions = { sand = 0.7, salt = 0.3 }");
  if (std::abs(sum - 1.0) > 1e-6)
    f.fail("fractions", "the mass fractions sum to " + short_number(sum) + ", not 1", "make them sum to 1");
  for (FeedSpecies& sp : spec.species) sp.fraction /= sum;  // exactly 1 for start_feed's check
  spec.velocity = f.get_vec3("velocity", {0, 0, 0});
  spec.start = read_number(f, kFeedFields.field("start"));
  spec.stop = read_number(f, kFeedFields.field("stop"));
  if (!(spec.stop > spec.start)) f.fail("stop", "the feed stops before it starts", "give stop > start");
  spec.interval = read_interval(f, s, kFeedFields);
  // One event places its grains one by one; a debt of millions per event is a typo, not a feed.
  double per_event = 0.0;
  for (const FeedSpecies& sp : spec.species) per_event += spec.mass_rate * sp.fraction * spec.interval / sp.mass;
  if (per_event > 1e6)
    f.fail("mass_rate",
           "each feed event would place " + short_number(per_event) + " grains (mass_rate x interval / grain mass)",
           "lower mass_rate or interval so that an event places at most 1,000,000 grains");
  spec.seed = static_cast<std::uint64_t>(
      f.get_int("seed", static_cast<std::int64_t>(s.seed) + 1000 + static_cast<std::int64_t>(index), 0,
                std::numeric_limits<std::int64_t>::max()));
  return spec;
}

}  // namespace

void read_flow(DemScene& s, const SceneNode& root) {
  std::size_t index = 0;
  for (const SceneNode& f : root.tables("feed")) s.flow.feeds.push_back(read_feed(s, f, index++));
  for (const SceneNode& o : root.tables("outlet")) {
    OutletSpec spec;
    spec.region = read_fill_region(o, s.gravity);
    spec.interval = read_interval(o, s, kOutletFields);
    s.flow.outlets.push_back(spec);
  }
}

std::size_t max_fed_grains(const DemScene& s) {
  double grains = 0.0;
  for (const FeedSpec& f : s.flow.feeds) {
    const double end = std::min(f.stop, s.duration);
    if (!(end > f.start)) continue;
    const double events = std::floor((end - f.start) / f.interval) + 1.0;
    for (const FeedSpecies& sp : f.species) grains += std::ceil(events * f.mass_rate * sp.fraction * f.interval / sp.mass);
  }
  return grains > 1e15 ? std::numeric_limits<std::size_t>::max() / 2 : static_cast<std::size_t>(grains);
}

}  // namespace gf
