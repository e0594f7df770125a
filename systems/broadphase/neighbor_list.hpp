// Verlet neighbour list of particle pairs and the contact history aligned with it.
// Half list: each pair appears once, owned by its lower row i (j > i), stored row by row (CSR).
#pragma once

#include <algorithm>
#include <array>
#include <string>
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

// Doubles of history a contact law may keep per contact (a wall contact keeps them in one
// 64-byte record).
inline constexpr std::size_t kMaxHistory = 8;

// Contact history of the pairs in contact at the last evaluation, packed in list order: `pair`
// holds each entry's list index, increasing, and `value[q]`, q < width, the law's history doubles
// (its component's fields, seen from the pair's owner row i). What they mean is the law's: this
// table, the broadphase and the checkpoint carry them by name and position only.
// Pairs apart have no entry, which is zero history.
// `slot` is the inverse map, per list pair: its entry, or -1 (any pair past its end has none), so
// the contact kernel finds a pair's history with one load instead of a merge.
struct PairHistory {
  std::string component;            // the law's history component, e.g. "hertz_mindlin.shear"
  std::vector<std::string> fields;  // its doubles' names, width of them
  double exchange_sign = -1.0;      // factor when the owner row changes: -1 for odd fields
  std::size_t width = 0;
  Column<std::int32_t> pair;
  std::array<ColumnD, kMaxHistory> value;
  Column<std::int32_t> slot;
  std::size_t size() const { return pair.size(); }
  // Sets the number of entries; `slot` is then stale until map_slots.
  void resize(std::size_t n) {
    pair.resize(n);
    for (std::size_t q = 0; q < width; ++q) value[q].resize(n);
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
  // Entry of list pair k, or -1 when it has no history.
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
