// Continuous operation in a DEM step: the feeds run first in each step (their grains join the table
// at that step's neighbour-list rebuild), the outlets last (their grains leave at the next step's).
// FlowState is the resource both keep their state in; it is checkpointed with the grains, so a run
// resumed across inserts and removals continues bit-identically.
#pragma once

#include <string_view>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/system.hpp"
#include "systems/flow/feed.hpp"
#include "systems/flow/outlet.hpp"

namespace gf {

// The scene's [[feed]] and [[outlet]] tables, in order.
struct FlowSpec {
  std::vector<FeedSpec> feeds;
  std::vector<OutletSpec> outlets;
  bool any() const { return !feeds.empty() || !outlets.empty(); }
};

struct FlowState {
  std::vector<FeedState> feeds;
  std::vector<OutletState> outlets;
  ResidenceLog residence;
  std::vector<ExitRecord> exits;  // grains counted out and not yet written (ResidenceOutput takes them)
  double fed_mass() const;
  std::int64_t fed_grains() const;
  double discharged_mass() const;
  std::int64_t discharged() const;
  double backlog() const;  // kg owed by every feed
};

// Starts every feed and outlet (std::invalid_argument from start_feed for a bad spec).
FlowState start_flow(const FlowSpec& spec);

// Whether feeds and outlets act in this step: not while settling or priming.
bool flow_moving(const StepContext& now);

// Stops the run (std::runtime_error naming the fix) when the owned rows and the queued grains pass
// max_grains, what the machine's memory holds.
void check_feed_room(const Grains& g, std::size_t max_grains);

// Holds the feed events due by the start of the step. Nothing is fed while settling or priming.
// A table that would grow past `max_grains` (what the machine's memory holds) stops the run with a
// std::runtime_error: the outlets take less than the feeds bring.
class FeedSystem : public SystemBase<FeedSystem> {
 public:
  using Reads = gf::Reads<Position, Radius>;
  using Writes = gf::Writes<FlowState>;
  FeedSystem(std::vector<FeedSpec> feeds, std::size_t max_grains) : feeds_(std::move(feeds)), max_(max_grains) {}
  std::string_view name() const override { return "feed"; }
  void run(World& world, const StepContext& now) override;

 private:
  std::vector<FeedSpec> feeds_;
  std::size_t max_;
};

// Counts out the grains inside an outlet at the end of the step (time t + dt).
class OutletSystem : public SystemBase<OutletSystem> {
 public:
  using Reads = gf::Reads<Position, ParticleId, Species, Mass>;
  using Writes = gf::Writes<FlowState>;
  explicit OutletSystem(std::vector<OutletSpec> outlets) : outlets_(std::move(outlets)) {}
  std::string_view name() const override { return "outlet"; }
  void run(World& world, const StepContext& now) override;

 private:
  std::vector<OutletSpec> outlets_;
};

void save_flow_state(CheckpointWriter& out, const FlowState& s);
// Restores a FlowState saved for a scene with the same feeds and outlets; a checkpoint written with
// other counts (or none) fails naming the fix.
void restore_flow_state(const CheckpointReader& in, FlowState& s, const FlowSpec& spec);

}  // namespace gf
