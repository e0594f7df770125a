// Continuous operation: grains fed into a region at a mass rate, removed where they reach an outlet,
// and the time each fed grain spent in between (its residence time).
//
// Feed. At each feed event (every `interval` seconds from `start` until `stop`) every species is owed
// rate * fraction * interval kg more (fractions by mass, summing to 1). As many whole grains as the
// owed mass pays for are placed at random in the feed region by place_random (wholly inside it,
// overlapping neither each other nor the grains already near it; largest first) with the feed's
// velocity and no spin (a species of a size distribution draws each grain's diameter before placing it, and
// the grain costs its own mass), and queued for insertion: they join the table at the next neighbour-list
// rebuild, which a queued change forces at the next step. What a grain costs is taken off its
// species' debt; the remainder carries over, so the mean rate is exact over many events whatever the
// grain mass. When the region has no free spot left (the bed has backed up into it) the grains not
// placed stay owed and are tried again at the next event: the debt is the backlog, reported, so a
// feed faster than the flow can take shows instead of being dropped. Event k draws from a generator
// seeded with (seed, k) alone, so a run and its resumed continuation place the same grains.
//
// Residence. The ids queue_insert hands out increase, so each event's grains hold one range of ids;
// ResidenceLog keeps, per event whose grains are not all gone, that range, its time and how many
// are left. A grain removed at the outlet finds its entry time by its id; grains present from the
// start (a fill) have none and are logged as not fed.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "engine/grains.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/fill/region.hpp"
#include "systems/fill/size_distribution.hpp"

namespace gf {

struct FeedSpecies {
  std::int32_t type = 0;
  double radius = 0.0;       // m
  double mass = 0.0;         // kg
  double inv_inertia = 0.0;  // 1/(kg m^2); 0 for species that do not rotate
  double fraction = 0.0;     // of the fed mass
  // A species of a size distribution: each grain draws its diameter, and costs its own mass (of this
  // density); `radius` is then the largest grain's and `mass` the smallest's. Null for one size.
  std::shared_ptr<const SizeDistribution> size = nullptr;
  double density = 0.0;  // kg/m^3
};

struct FeedSpec {
  Region region;
  double mass_rate = 0.0;  // kg/s, all species together
  std::vector<FeedSpecies> species;
  std::array<double, 3> velocity{};  // m/s of a new grain
  double start = 0.0;                // s
  double stop = std::numeric_limits<double>::infinity();
  double interval = 0.0;             // s between events (> 0)
  std::uint64_t seed = 1;
  std::size_t attempts = 200;        // random tries per grain and event before it waits for the next
};

// One event's grains: ids [first, first + count), fed at `time`, `left` of them still in the table.
struct FeedBatch {
  std::int64_t first = 0;
  std::int64_t count = 0;
  std::int64_t left = 0;
  double time = 0.0;
};

struct ResidenceLog {
  std::vector<FeedBatch> batches;  // increasing ids; batches whose grains have all left are dropped
  // The entry time of grain `id`, if it was fed; counts it out of its batch when `leaving`.
  std::optional<double> entry(std::int64_t id, bool leaving);
};

struct FeedState {
  std::int64_t events = 0;    // events held so far
  double next = 0.0;          // s, the next event's time
  std::vector<double> owed;   // kg per feed species
  double fed_mass = 0.0;      // kg queued so far
  std::int64_t fed_grains = 0;
  double backlog() const;     // kg owed but not yet placed, beyond what one grain of each costs
};

// Starts a feed's state (the first event at `start`). std::invalid_argument names what is wrong with
// a spec (no species, fractions not summing to 1, non-positive rate, interval, radius or mass).
FeedState start_feed(const FeedSpec& spec);

// The owned grains whose spheres reach into the region's bounding box grown by `margin`: the only
// ones of the table a grain placed in the region could overlap.
std::vector<PlacedGrain> owned_grains_near(const Grains& g, const Region& region, double margin);

// Holds every event due at time t (there may be several when the interval is shorter than a step):
// places and queues the grains the debt pays for, and logs their batches. Returns the grains queued.
// `elsewhere`: grains near the region that are not g's owned rows (another rank's), which the new
// grains must not overlap either; the placement depends on the set of grains, not their order.
std::int64_t feed_events(Grains& g, const FeedSpec& spec, FeedState& state, ResidenceLog& log, double t,
                         std::span<const PlacedGrain> elsewhere = {});

}  // namespace gf
