#include "systems/decomposition/mpi/rank_flow.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>
#include <vector>

namespace gf {

namespace {

template <class T>
std::vector<std::byte> bytes_of(const std::vector<T>& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<std::byte> out(v.size() * sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
}

template <class T>
std::vector<T> records_of(const std::vector<std::byte>& bytes) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (bytes.size() % sizeof(T) != 0) throw std::runtime_error("a flow message is not whole records");
  std::vector<T> out(bytes.size() / sizeof(T));
  if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
  return out;
}

// Every rank's `mine`, in rank order (this rank's own included).
template <class T>
std::vector<std::vector<T>> share(const std::vector<T>& mine, const MpiContext& mpi) {
  const std::vector<std::byte> out = bytes_of(mine);
  const auto all = mpi.exchange(std::vector<std::vector<std::byte>>(static_cast<std::size_t>(mpi.size()), out));
  std::vector<std::vector<T>> in;
  in.reserve(all.size());
  for (const auto& b : all) in.push_back(records_of<T>(b));
  return in;
}

bool feed_due(const FeedSpec& spec, const FeedState& s, double t) { return s.next <= t && s.next < spec.stop; }

}  // namespace

void rank_feed_events(Grains& g, const FlowSpec& spec, FlowState& s, const Rcb& rcb, const MpiContext& mpi,
                      double t, std::size_t max_grains) {
  const std::size_t before = g.pending.insert.size();
  for (std::size_t k = 0; k < spec.feeds.size(); ++k) {
    const FeedSpec& f = spec.feeds[k];
    if (!feed_due(f, s.feeds[k], t)) continue;  // alike on every rank
    double largest = 0.0;
    for (const FeedSpecies& sp : f.species) largest = std::max(largest, sp.radius);
    const std::vector<std::vector<PlacedGrain>> all = share(owned_grains_near(g, f.region, largest), mpi);
    std::vector<PlacedGrain> elsewhere;
    for (std::size_t r = 0; r < all.size(); ++r)
      if (static_cast<int>(r) != mpi.rank())  // feed_events takes this rank's own rows
        elsewhere.insert(elsewhere.end(), all[r].begin(), all[r].end());
    feed_events(g, f, s.feeds[k], s.residence, t, elsewhere);
  }
  // Every rank queued the same grains: each keeps those in its box.
  auto& queued = g.pending.insert;
  const auto mine = std::stable_partition(queued.begin() + static_cast<std::ptrdiff_t>(before), queued.end(),
                                          [&](const GrainRow& r) { return rcb.owner_of({r.x[0], r.x[1], r.x[2]}) == mpi.rank(); });
  queued.erase(mine, queued.end());
  check_feed_room(g, max_grains);
}

void rank_outlet_pass(Grains& g, const FlowSpec& spec, FlowState& s, const MpiContext& mpi, double t) {
  for (std::size_t k = 0; k < spec.outlets.size(); ++k) {
    OutletState& o = s.outlets[k];
    if (t < o.next) continue;  // alike on every rank
    const OutletState before = o;
    // This rank's grains out, their entries counted off the log; then every rank's records.
    const std::vector<ExitRecord> mine = outlet_pass(g, spec.outlets[k], o, s.residence, t);
    const std::vector<std::vector<ExitRecord>> all = share(mine, mpi);
    o.discharged_mass = before.discharged_mass;
    o.discharged = before.discharged;
    for (std::size_t r = 0; r < all.size(); ++r)
      for (const ExitRecord& e : all[r]) {
        o.discharged_mass += e.mass;
        ++o.discharged;
        if (static_cast<int>(r) != mpi.rank()) s.residence.entry(e.id, true);
        s.exits.push_back(e);
      }
  }
}

}  // namespace gf
