#include "systems/flow/feed.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "systems/fill/random_fill.hpp"

namespace gf {

namespace {

// SplitMix64's finaliser: a well-mixed seed from (seed, event, grain), so nearby events do not
// start their generators from nearby states.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// Every grain a new one could overlap: the owned grains near the region, the grains queued in
// earlier events, and those near it elsewhere (another rank's).
std::vector<PlacedGrain> grains_near(const Grains& g, const Region& region, double margin,
                                     std::span<const PlacedGrain> elsewhere) {
  std::vector<PlacedGrain> near = owned_grains_near(g, region, margin);
  // Grains queued in earlier events but not yet in the table occupy their spots too.
  for (const GrainRow& r : g.pending.insert) near.push_back({{r.x[0], r.x[1], r.x[2]}, r.type, r.radius});
  near.insert(near.end(), elsewhere.begin(), elsewhere.end());
  return near;
}

struct Grain {
  double radius, mass, inv_inertia;
};

// The next grain of a species: a fixed size's own values, or a diameter drawn from its distribution by a
// generator of its own seeded from the placement's seed.
Grain next_grain(const FeedSpecies& sp, std::uint64_t seed) {
  if (!sp.size) return {sp.radius, sp.mass, sp.inv_inertia};
  std::mt19937_64 rng(mix(seed ^ 0x73697a65ull));
  const double d = sp.size->draw(rng), m = sphere_mass(sp.density, d);
  return {0.5 * d, m, sp.inv_inertia > 0.0 ? 1.0 / (0.1 * m * d * d) : 0.0};
}

}  // namespace

std::vector<PlacedGrain> owned_grains_near(const Grains& g, const Region& region, double margin) {
  const auto lo = region.bbox_lo(), hi = region.bbox_hi();
  std::vector<PlacedGrain> near;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const std::array<double, 3> p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
    const double reach = g.radius.r[i] + margin;
    bool in = true;
    for (int d = 0; d < 3 && in; ++d) in = p[d] > lo[d] - reach && p[d] < hi[d] + reach;
    if (in) near.push_back({p, g.species.type[i], g.radius.r[i]});
  }
  return near;
}

std::optional<double> ResidenceLog::entry(std::int64_t id, bool leaving) {
  auto it = std::upper_bound(batches.begin(), batches.end(), id,
                             [](std::int64_t v, const FeedBatch& b) { return v < b.first; });
  if (it == batches.begin()) return std::nullopt;
  --it;
  if (id >= it->first + it->count) return std::nullopt;
  const double t = it->time;
  if (leaving && --it->left <= 0) batches.erase(it);
  return t;
}

double FeedState::backlog() const {
  double kg = 0.0;
  for (const double o : owed) kg += std::max(0.0, o);
  return kg;
}

FeedState start_feed(const FeedSpec& spec) {
  if (spec.species.empty()) throw std::invalid_argument("feed: no species to feed");
  double sum = 0.0;
  for (const FeedSpecies& s : spec.species) {
    if (!(s.radius > 0.0) || !(s.mass > 0.0) || !(s.fraction >= 0.0))
      throw std::invalid_argument("feed: a species needs a positive radius and mass and a fraction >= 0");
    sum += s.fraction;
  }
  if (!(std::abs(sum - 1.0) <= 1e-9))
    throw std::invalid_argument("feed: the species' mass fractions sum to " + std::to_string(sum) + ", not 1");
  if (!(spec.mass_rate > 0.0) || !std::isfinite(spec.mass_rate) || !(spec.interval > 0.0) ||
      !std::isfinite(spec.interval) || !(spec.start >= 0.0) || !(spec.stop > spec.start) || spec.attempts == 0)
    throw std::invalid_argument("feed: mass_rate and interval must be positive and finite, 0 <= start < stop");
  if (const std::string p = spec.region.problem(); !p.empty()) throw std::invalid_argument("feed: region: " + p);
  FeedState s;
  s.next = spec.start;
  s.owed.assign(spec.species.size(), 0.0);
  return s;
}

std::int64_t feed_events(Grains& g, const FeedSpec& spec, FeedState& state, ResidenceLog& log, double t,
                         std::span<const PlacedGrain> elsewhere) {
  std::int64_t queued = 0;
  double largest = 0.0;
  for (const FeedSpecies& s : spec.species) largest = std::max(largest, s.radius);
  while (state.next <= t && state.next < spec.stop) {
    const double time = state.next;
    std::vector<PlacedGrain> taken = grains_near(g, spec.region, largest, elsewhere);
    FeedBatch batch{g.next_id, 0, 0, time};
    // Largest grains first (small ones fit between them), then by the order given.
    std::vector<std::size_t> order(spec.species.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return spec.species[a].radius > spec.species[b].radius; });
    std::uint64_t draw = 0;
    for (const std::size_t k : order) {
      const FeedSpecies& sp = spec.species[k];
      state.owed[k] += spec.mass_rate * sp.fraction * spec.interval;
      for (;;) {
        const std::uint64_t seed = mix(mix(spec.seed ^ mix(static_cast<std::uint64_t>(state.events))) + draw);
        const Grain next = next_grain(sp, seed);
        if (state.owed[k] < next.mass) break;
        ++draw;
        std::vector<PlacedGrain> one;
        try {
          one = place_random(spec.region, {{sp.type, next.radius, 1}}, seed, taken, spec.attempts);
        } catch (const FillError&) {
          break;  // no room now: the debt waits for the next event
        }
        GrainRow row;
        for (int d = 0; d < 3; ++d) {
          row.x[d] = one[0].x[d];
          row.v[d] = spec.velocity[d];
        }
        row.radius = next.radius;
        row.mass = next.mass;
        row.inv_inertia = next.inv_inertia;
        row.type = sp.type;
        g.queue_insert(row);
        taken.push_back(one[0]);
        state.owed[k] -= next.mass;
        state.fed_mass += next.mass;
        ++batch.count;
      }
    }
    batch.left = batch.count;
    if (batch.count > 0) log.batches.push_back(batch);
    queued += batch.count;
    state.fed_grains += batch.count;
    ++state.events;
    state.next = spec.start + static_cast<double>(state.events) * spec.interval;
  }
  return queued;
}

}  // namespace gf
