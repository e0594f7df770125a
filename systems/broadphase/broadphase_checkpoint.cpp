#include "systems/broadphase/broadphase_checkpoint.hpp"

#include <algorithm>
#include <cstdint>

#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

namespace {

template <class T>
bool all_below(const T& v, std::size_t n) {
  return std::all_of(v.begin(), v.end(), [n](auto x) { return x >= 0 && static_cast<std::size_t>(x) < n; });
}

}  // namespace

void save_broadphase(CheckpointWriter& out, const BroadphaseState& bp, const std::string& prefix) {
  const std::string p = prefix + "broadphase.";
  out.value(p + "skin", bp.skin);
  out.value(p + "valid", bp.valid);
  out.value(p + "force_rebuild", bp.force_rebuild);
  out.value(p + "rebuilds", bp.rebuilds);
  out.value(p + "checks", bp.checks);
  out.value(p + "kept", bp.cover.kept);
}

void restore_broadphase(const CheckpointReader& in, BroadphaseState& bp, const std::string& prefix) {
  const std::string p = prefix + "broadphase.";
  bp.valid = in.value<bool>(p + "valid");
  bp.force_rebuild = in.value<bool>(p + "force_rebuild");
  bp.rebuilds = in.value<std::int64_t>(p + "rebuilds");
  bp.checks = in.value<std::int64_t>(p + "checks");
  bp.cover.kept = in.has(p + "kept") ? in.value<std::int64_t>(p + "kept") : 0;
}

void check_list_sections(const CheckpointReader& in, const NeighborList& l, const PairHistory& h,
                         const BroadphaseState& bp, const Grains& g) {
  const std::size_t pairs = l.pairs();
  in.require(l.offsets.empty() || (l.offsets.size() == g.n_owned + 1 && l.offsets.front() == 0 &&
                                   l.offsets.back() == pairs && std::is_sorted(l.offsets.begin(), l.offsets.end())),
             "neighbour list offsets", kFixResumeOrStateFile);
  in.require(l.i.size() == pairs && l.key.size() == pairs && l.type_pair.size() >= pairs &&
                 l.i_lane.size() >= pairs && l.j_lane.size() >= pairs,
             "neighbour list lengths", kFixResumeOrStateFile);
  in.require(all_below(l.i, g.n_owned) && all_below(l.j, g.n) && all_below(l.i_lane, g.n) &&
                 all_below(l.j_lane, g.n) && all_below(l.type_pair, static_cast<std::size_t>(kMaxSpecies * kMaxSpecies)),
             "neighbour list rows", kFixResumeOrStateFile);
  in.require(all_below(h.pair, pairs) && std::is_sorted(h.pair.begin(), h.pair.end()), "contact history pairs", kFixResumeOrStateFile);
  for (std::size_t q = 0; q < h.width; ++q) in.require(h.value[q].size() == h.size(), "contact history lengths", kFixResumeOrStateFile);
  in.require(std::all_of(h.slot.begin(), h.slot.end(),
                         [&](std::int32_t s) { return s >= -1 && s < static_cast<std::int64_t>(h.size()); }),
             "contact history slots", kFixResumeOrStateFile);
  in.require(bp.ref_x.size() == bp.ref_y.size() && bp.ref_y.size() == bp.ref_z.size() &&
                 (bp.ref_x.empty() || bp.ref_x.size() == g.n),
             "skin reference positions", kFixResumeOrStateFile);
}

}  // namespace gf
