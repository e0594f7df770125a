#include "systems/flow/flow_systems.hpp"

#include <stdexcept>
#include <string>

namespace gf {

bool flow_moving(const StepContext& now) { return !now.prime && now.stage != "settle"; }

double FlowState::fed_mass() const {
  double kg = 0.0;
  for (const FeedState& f : feeds) kg += f.fed_mass;
  return kg;
}
std::int64_t FlowState::fed_grains() const {
  std::int64_t n = 0;
  for (const FeedState& f : feeds) n += f.fed_grains;
  return n;
}
double FlowState::discharged_mass() const {
  double kg = 0.0;
  for (const OutletState& o : outlets) kg += o.discharged_mass;
  return kg;
}
std::int64_t FlowState::discharged() const {
  std::int64_t n = 0;
  for (const OutletState& o : outlets) n += o.discharged;
  return n;
}
double FlowState::backlog() const {
  double kg = 0.0;
  for (const FeedState& f : feeds) kg += f.backlog();
  return kg;
}

FlowState start_flow(const FlowSpec& spec) {
  FlowState s;
  for (const FeedSpec& f : spec.feeds) s.feeds.push_back(start_feed(f));
  s.outlets.resize(spec.outlets.size());
  return s;
}

void FeedSystem::run(World& world, const StepContext& now) {
  if (!flow_moving(now)) return;
  FlowState& s = world.resources.get<FlowState>();
  Grains& g = world.grains;
  for (std::size_t k = 0; k < feeds_.size(); ++k) feed_events(g, feeds_[k], s.feeds[k], s.residence, now.t);
  check_feed_room(g, max_);
}

void check_feed_room(const Grains& g, std::size_t max_grains) {
  if (g.n_owned + g.pending.insert.size() > max_grains)
    throw std::runtime_error("the feeds have brought the grains to " +
                             std::to_string(g.n_owned + g.pending.insert.size()) + ", more than the " +
                             std::to_string(max_grains) +
                             " this machine's memory holds: the outlets take less than the feeds bring. Fix: an "
                             "[[outlet]] where the grains collect, a lower mass_rate, or a stop time for the feed");
}

void OutletSystem::run(World& world, const StepContext& now) {
  if (!flow_moving(now)) return;
  FlowState& s = world.resources.get<FlowState>();
  for (std::size_t k = 0; k < outlets_.size(); ++k) {
    std::vector<ExitRecord> out = outlet_pass(world.grains, outlets_[k], s.outlets[k], s.residence, now.t + now.dt);
    s.exits.insert(s.exits.end(), out.begin(), out.end());
  }
}

void save_flow_state(CheckpointWriter& out, const FlowState& s) {
  out.value("flow.feeds", static_cast<std::uint64_t>(s.feeds.size()));
  out.value("flow.outlets", static_cast<std::uint64_t>(s.outlets.size()));
  for (std::size_t k = 0; k < s.feeds.size(); ++k) {
    const std::string p = "flow.feed." + std::to_string(k) + ".";
    out.value(p + "events", s.feeds[k].events);
    out.value(p + "next", s.feeds[k].next);
    out.value(p + "fed_mass", s.feeds[k].fed_mass);
    out.value(p + "fed_grains", s.feeds[k].fed_grains);
    out.vector(p + "owed", s.feeds[k].owed);
  }
  out.vector("flow.outlet_states", s.outlets);
  out.vector("flow.residence", s.residence.batches);
  out.vector("flow.exits", s.exits);
}

void restore_flow_state(const CheckpointReader& in, FlowState& s, const FlowSpec& spec) {
  const std::string fix = "resume with the scene's original [[feed]] and [[outlet]] tables";
  if (!in.has("flow.feeds"))
    in.fail("it was written by a run without [[feed]] or [[outlet]] tables", fix);
  if (in.value<std::uint64_t>("flow.feeds") != spec.feeds.size() ||
      in.value<std::uint64_t>("flow.outlets") != spec.outlets.size())
    in.fail("it was written with " + std::to_string(in.value<std::uint64_t>("flow.feeds")) + " feeds and " +
                std::to_string(in.value<std::uint64_t>("flow.outlets")) + " outlets, the scene now has " +
                std::to_string(spec.feeds.size()) + " and " + std::to_string(spec.outlets.size()),
            fix);
  for (std::size_t k = 0; k < s.feeds.size(); ++k) {
    const std::string p = "flow.feed." + std::to_string(k) + ".";
    s.feeds[k].events = in.value<std::int64_t>(p + "events");
    s.feeds[k].next = in.value<double>(p + "next");
    s.feeds[k].fed_mass = in.value<double>(p + "fed_mass");
    s.feeds[k].fed_grains = in.value<std::int64_t>(p + "fed_grains");
    in.vector(p + "owed", s.feeds[k].owed);
    if (s.feeds[k].owed.size() != spec.feeds[k].species.size())
      in.fail("feed " + std::to_string(k) + " had another number of species", fix);
  }
  in.vector("flow.outlet_states", s.outlets);
  in.vector("flow.residence", s.residence.batches);
  in.vector("flow.exits", s.exits);
  if (s.outlets.size() != spec.outlets.size()) in.fail("its outlet states are inconsistent", fix);
}

}  // namespace gf
