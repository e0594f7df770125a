// Verlet neighbour list of particle pairs and the contact history aligned with it.
// Half list: each pair appears once, owned by its lower row i (j > i), stored row by row (CSR).
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "engine/column.hpp"

namespace gf {

// Scenes define at most this many species (the scene loader enforces it), so a type pair has a
// fixed index whatever the table: species_i * kMaxSpecies + species_j.
inline constexpr std::int64_t kMaxSpecies = 64;

struct NeighborList {
  std::vector<std::uint32_t> offsets;   // size n_owned + 1
  std::vector<std::uint32_t> i;         // owner row of each pair
  std::vector<std::uint32_t> j;         // partner row of each pair
  Column<std::int32_t> i_lane, j_lane;  // the same as SIMD gather indices, padded with row 0
  Column<std::int32_t> type_pair;       // species[i] * kMaxSpecies + species[j], to index pair tables
  std::vector<std::uint64_t> key;       // (min id << 32 | max id): identifies a pair across rebuilds
  std::size_t pairs() const { return j.size(); }
};

// Contact history (seed 000 Table 1 springs) of the pairs in contact at the last evaluation, packed
// in list order: `pair` holds each spring's list index, increasing, and the six columns its values.
// Pairs apart have no entry, which is a zero spring. Springs are seen from the pair's owner row i.
// `slot` is the inverse map, per list pair: its entry, or -1 (any pair past its end has none), so
// the contact kernel finds a pair's spring with one load instead of a merge.
struct PairHistory {
  Column<std::int32_t> pair;
  ColumnD sx, sy, sz;  // tangential spring, m
  ColumnD rx, ry, rz;  // rolling angle, rad
  Column<std::int32_t> slot;
  std::size_t size() const { return pair.size(); }
  // Sets the number of entries; `slot` is then stale until map_slots.
  void resize(std::size_t n) {
    pair.resize(n);
    for (ColumnD* c : {&sx, &sy, &sz, &rx, &ry, &rz}) c->resize(n);
  }
  // Rebuilds `slot` for a list of `pairs` list pairs from `pair`.
  void map_slots(std::size_t pairs) {
    slot.assign(pairs, -1);
    for (std::size_t e = 0; e < size(); ++e) slot[static_cast<std::size_t>(pair[e])] = static_cast<std::int32_t>(e);
  }
  void clear() {
    resize(0);
    std::fill(slot.begin(), slot.end(), -1);
  }
  // Entry of list pair k, or -1 when it has no spring.
  std::int64_t find(std::size_t k) const {
    const std::int32_t* b = pair.begin();
    const std::int32_t* e = pair.end();
    const std::int32_t* it = std::lower_bound(b, e, static_cast<std::int32_t>(k));
    return it != e && *it == static_cast<std::int32_t>(k) ? it - b : -1;
  }
};

inline std::uint64_t pair_key(std::int64_t a, std::int64_t b) {
  const auto lo = static_cast<std::uint64_t>(a < b ? a : b);
  const auto hi = static_cast<std::uint64_t>(a < b ? b : a);
  return lo << 32 | hi;
}

}  // namespace gf
