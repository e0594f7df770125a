// Several processes sharing each evaluation of the bodies' contacts (grainflow_mpi runs body scenes
// this way). Every process holds the same bodies, members and member-pair list and steps them alike;
// each evaluates every R-th listed pair and every R-th member against the walls (process r those of
// index r mod R, so that each takes pairs from every part of the list), and `share` hands every
// process's touching outcomes to all. Each process then sums the same outcomes in the same order as
// one process does, so the state stays bit-identical to a run on one process, for any number of them. What is replicated (the list, the members' placement,
// the integration) is a few per cent of a body step; the contacts are the rest.
//
// A record (native byte order: the processes run one build on one kind of machine):
//   u64 a hash of the bodies' state the process evaluated (positions, orientations, velocities,
//       spins): the processes compare them, and a difference (ranks on machines or builds that
//       round differently) stops every one at that step, rather than letting their states drift apart
//   per touching pair of its share:   u32 list index, delta, force 3, torque_a 3, torque_b 3,
//                                      the law's history (width)
//   per member of its share touching a wall: u32 member, delta, force 3, torque_a 3, u32 planes
//                                      touching, then per plane: u32 plane, its history (width)
// each list preceded by its u64 count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "systems/bodies/contact_outcome.hpp"

namespace gf {

struct MemberWallHistory;
struct Bodies;

// The hash of the records: of the bytes of the bodies' position, orientation, velocity and spin columns.
std::uint64_t body_state_hash(const Bodies& bodies);

struct BodyContactSplit {
  int rank = 0, ranks = 1;
  // Collective: takes this process's bytes, returns every process's (element r from process r).
  std::function<std::vector<std::vector<std::byte>>(std::vector<std::byte>)> share;
};

// The items a process evaluates, of the list pairs and of the members alike: index i is its own
// where i mod stride = offset (one process: all).
struct SplitBlocks {
  std::size_t offset = 0, stride = 1;
  bool mine(std::size_t i) const { return i % stride == offset; }
  // How many of n items are its own; the j-th of them is item(j).
  std::size_t count(std::size_t n) const { return n > offset ? (n - offset + stride - 1) / stride : 0; }
  std::size_t item(std::size_t j) const { return offset + j * stride; }
};
SplitBlocks split_blocks(const BodyContactSplit& split);

// Packs the touching outcomes of this process's items and its members' wall springs and loads.
std::vector<std::byte> pack_outcomes(std::uint64_t hash, std::span<const ContactOutcome> pairs, std::size_t pair_width,
                                     std::span<const ContactOutcome> walls, const MemberWallHistory& springs,
                                     const SplitBlocks& mine);
// Writes another process's records into pairs, walls and the wall springs and loads; returns its hash.
// Throws std::runtime_error when the bytes are not whole records of these sizes.
std::uint64_t unpack_outcomes(std::span<const std::byte> bytes, std::span<ContactOutcome> pairs, std::size_t pair_width,
                              std::span<ContactOutcome> walls, MemberWallHistory& springs);
// The whole evaluation on every process: the wall springs of the members not its own are cleared
// (apart, as one process leaves them), then every other process's records written in.
// Returns false when some process evaluated another state (its hash differs from `hash`): every
// process then finds a difference at the same step.
bool share_outcomes(const BodyContactSplit& split, std::uint64_t hash, std::span<ContactOutcome> pairs,
                    std::size_t pair_width, std::span<ContactOutcome> walls, MemberWallHistory& springs,
                    const SplitBlocks& mine);

}  // namespace gf
