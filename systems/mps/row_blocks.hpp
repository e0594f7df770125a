// Fixed blocks of rows for the pressure solvers' passes: each pass runs over blocks of kRowBlock rows in
// parallel, and a reduction is summed per block and then over the blocks in order, so its value does not
// depend on the thread count (bit for bit). And one compressed row times a vector, on SIMD batches.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "engine/simd.hpp"

namespace gf {

inline constexpr std::size_t kRowBlock = 1024;  // a multiple of every SIMD width

inline std::size_t row_blocks(std::size_t n) { return (n + kRowBlock - 1) / kRowBlock; }

// body(block, first row, end row) for every fixed block of rows, in parallel.
template <class F>
void for_row_blocks(std::size_t n, F&& body) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, row_blocks(n), 1), [&](const tbb::blocked_range<std::size_t>& br) {
    for (std::size_t b = br.begin(); b < br.end(); ++b) body(b, b * kRowBlock, std::min(n, (b + 1) * kRowBlock));
  });
}

// The blocks' partial sums, added in block order.
inline double sum_in_order(const std::vector<double>& part) {
  double t = 0;
  for (double v : part) t += v;
  return t;
}

// sum_k val[k] v[col[k]] over row i of a compressed-row matrix: kLanes couplings at a time (one hardware gather
// of v each), the rest one by one, so the sum is not one chain of dependent additions; the order is fixed by the
// row's length alone. Columns are below 2^31.
inline double row_dot(const std::uint32_t* start, const std::uint32_t* col, const double* val, std::size_t i,
                      const double* v) {
  const auto* col32 = reinterpret_cast<const std::int32_t*>(col);
  std::uint32_t k = start[i];
  const std::uint32_t end = start[i + 1];
  BatchD acc(0.0);
  for (; k + kLanes <= end; k += kLanes) acc = xsimd::fma(BatchD::load_unaligned(val + k), gather32(v, col32 + k), acc);
  double tail = 0;
  for (; k < end; ++k) tail += val[k] * v[col[k]];
  return xsimd::hadd(acc) + tail;
}

}  // namespace gf
