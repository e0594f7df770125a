// The wall drivers' loop over fixed blocks of rows (wall_contact_kernels.hpp's scalar twin, the mesh
// walls): blocks run in parallel, each keeping its own worst overlap and its per-wall sums of force and
// moment (six numbers a wall, walls.hpp), which are then added in block order, so the loads do not
// depend on which thread ran which block.
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>
#include <vector>

namespace gf {

// The per-wall sums (6 * walls) of blocks' records laid out block after block, added in block order.
inline std::vector<double> add_wall_blocks(const std::vector<double>& blocks, std::size_t walls) {
  std::vector<double> sums(walls * 6, 0.0);
  for (std::size_t at = 0; at + walls * 6 <= blocks.size(); at += walls * 6)
    for (std::size_t k = 0; k < walls * 6; ++k) sums[k] += blocks[at + k];
  return sums;
}

// Calls body(first, last, load, worst) for each block of `block` rows of [0, n): `load` points at the
// block's 6 * walls sums (zeroed), `worst` (from -inf) is the block's largest overlap past the limit.
// Fills `sums` (6 * walls, the blocks' sums in block order) and returns whether some worst is > 0.
template <class Body>
bool for_wall_row_blocks(std::size_t n, std::size_t block, std::size_t walls, std::vector<double>& sums, Body&& body) {
  const std::size_t nblocks = (n + block - 1) / block;
  std::vector<double> worst(nblocks, -std::numeric_limits<double>::infinity());
  std::vector<double> load(nblocks * walls * 6, 0.0);
  tbb::parallel_for(std::size_t(0), nblocks, [&](std::size_t b) {
    body(b * block, std::min(n, (b + 1) * block), &load[b * walls * 6], worst[b]);
  });
  sums = add_wall_blocks(load, walls);
  return std::any_of(worst.begin(), worst.end(), [](double w) { return w > 0.0; });
}

}  // namespace gf
