// Shared by the tests run on several ranks: the communicator, and grains whose every column byte is
// a function of the grain's id, so a rank can check a row it received without seeing the sender's.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/decomposition/row_bytes.hpp"

namespace gf::test {

const MpiContext& test_world();

// Byte b of column c of the grain with this id.
inline std::byte id_byte(std::int64_t id, std::size_t c, std::size_t b) {
  std::uint64_t h = static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull ^ (c * 0xBF58476D1CE4E5B9ull + b);
  h ^= h >> 31;
  h *= 0x94D049BB133111EBull;
  return static_cast<std::byte>(h >> 56);
}

// Fills every column of `row` from the id, then the id and the position.
inline void stamp_row(Grains& g, std::size_t row, std::int64_t id, const std::array<double, 3>& p) {
  const std::vector<RawColumn> cols = raw_row_columns(g);
  for (std::size_t c = 0; c < cols.size(); ++c)
    for (std::size_t b = 0; b < cols[c].elem_size; ++b)
      static_cast<std::byte*>(cols[c].data)[row * cols[c].elem_size + b] = id_byte(id, c, b);
  g.pid.id[row] = id;
  g.pos.x[row] = p[0], g.pos.y[row] = p[1], g.pos.z[row] = p[2];
}

// Whether every column of row a of g holds the bytes of row b of ref.
inline bool same_row(Grains& g, std::size_t a, Grains& ref, std::size_t b) {
  const std::vector<RawColumn> x = raw_row_columns(g), y = raw_row_columns(ref);
  if (x.size() != y.size()) return false;
  for (std::size_t c = 0; c < x.size(); ++c)
    if (x[c].elem_size != y[c].elem_size ||
        std::memcmp(static_cast<const std::byte*>(x[c].data) + a * x[c].elem_size,
                    static_cast<const std::byte*>(y[c].data) + b * y[c].elem_size, x[c].elem_size) != 0)
      return false;
  return true;
}

}  // namespace gf::test
