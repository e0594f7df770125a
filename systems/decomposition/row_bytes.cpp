#include "systems/decomposition/row_bytes.hpp"

#include <cstring>
#include <stdexcept>
#include <string>

namespace gf {

namespace {

std::vector<RawColumn> columns(Grains& g, bool core_only) {
  std::vector<RawColumn> out;
  g.for_each_core_column([&out](auto& col) { out.push_back({col.data(), sizeof(*col.data()), col.size()}); });
  if (core_only) return out;
  for (const RawColumn& c : g.extras.raw_columns()) out.push_back(c);
  return out;
}

}  // namespace

std::vector<RawColumn> raw_row_columns(Grains& g) { return columns(g, false); }

std::size_t row_bytes(Grains& g, bool core_only) {
  std::size_t b = 0;
  for (const RawColumn& c : columns(g, core_only)) b += c.elem_size;
  return b;
}

std::size_t packed_rows(Grains& g, std::size_t bytes, bool core_only) {
  const std::size_t rb = row_bytes(g, core_only);
  if (rb == 0 || bytes % rb != 0)
    throw std::invalid_argument("received " + std::to_string(bytes) + " bytes, not whole rows of " + std::to_string(rb) +
                                " bytes: the ranks' tables hold different columns");
  return bytes / rb;
}

void pack_rows(Grains& g, std::span<const std::uint32_t> rows, std::vector<std::byte>& out, bool core_only) {
  const std::vector<RawColumn> cols = columns(g, core_only);
  const std::size_t rb = row_bytes(g, core_only);
  std::size_t at = out.size();
  out.resize(at + rows.size() * rb);
  for (std::uint32_t r : rows)
    for (const RawColumn& c : cols) {
      std::memcpy(out.data() + at, static_cast<const std::byte*>(c.data) + r * c.elem_size, c.elem_size);
      at += c.elem_size;
    }
}

std::size_t unpack_rows(Grains& g, std::span<const std::byte> bytes, std::size_t first, bool core_only) {
  const std::size_t count = packed_rows(g, bytes.size(), core_only);
  const std::vector<RawColumn> cols = columns(g, core_only);
  std::size_t at = 0;
  for (std::size_t k = 0; k < count; ++k)
    for (const RawColumn& c : cols) {
      std::memcpy(static_cast<std::byte*>(c.data) + (first + k) * c.elem_size, bytes.data() + at, c.elem_size);
      at += c.elem_size;
    }
  return count;
}

std::size_t keep_and_append(Grains& g, std::span<const std::uint32_t> keep, std::span<const std::byte> bytes) {
  const std::size_t count = packed_rows(g, bytes.size());
  g.permute(keep);
  g.resize(keep.size() + count);
  return unpack_rows(g, bytes, keep.size());
}

}  // namespace gf
