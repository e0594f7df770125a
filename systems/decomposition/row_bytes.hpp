// Whole rows of the Grains table as bytes, for moving rows between ranks: every core column
// (without rotation, not the spin columns) in the table's component order, then every attached
// column (wall springs, mesh slots, ...) in attach order. A packed row is the concatenation of its
// elements in that column order, so rows pack and unpack one at a time with no per-column headers.
// Both sides must hold the same columns (tables set up by the same scene): the row size checks it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "engine/grains.hpp"

namespace gf {

// Every column of the table as raw storage: core columns, then attached ones.
std::vector<RawColumn> raw_row_columns(Grains& g);
// Bytes of one packed row (with core_only, of the core columns alone).
std::size_t row_bytes(Grains& g, bool core_only = false);

// Appends the given rows, packed, to out.
void pack_rows(Grains& g, std::span<const std::uint32_t> rows, std::vector<std::byte>& out, bool core_only = false);
// Writes packed rows into rows [first, first + count) (which must exist) of every column packed.
// Throws std::invalid_argument when the bytes are not whole rows of this table.
std::size_t unpack_rows(Grains& g, std::span<const std::byte> bytes, std::size_t first, bool core_only = false);
// The number of whole packed rows in `bytes`; throws std::invalid_argument if they are not whole.
std::size_t packed_rows(Grains& g, std::size_t bytes, bool core_only = false);

// Keeps the owned rows `keep` (in that order) and appends the packed rows after them as owned
// rows; ghost rows are dropped. Returns the number appended.
std::size_t keep_and_append(Grains& g, std::span<const std::uint32_t> keep, std::span<const std::byte> bytes);

}  // namespace gf
