// The one place xsimd is included (after engine/column.hpp, which brings the intrinsics with GCC
// bug 105593's false warning silenced: engine/intrinsics.hpp); xsimd's own headers are silenced the
// same way.
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/column.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <xsimd/xsimd.hpp>
#pragma GCC diagnostic pop

namespace gf {
// Kernels are compiled for the build machine's widest vectors (-march=native), or for 256-bit
// AVX2 when GRAINFLOW_SIMD_256 is defined (on CPUs that split 512-bit gathers, it can be faster).
#if defined(GRAINFLOW_SIMD_256) && defined(__AVX2__)
using SimdArch = xsimd::fma3<xsimd::avx2>;
#else
using SimdArch = xsimd::default_arch;
#endif
using BatchD = xsimd::batch<double, SimdArch>;
inline constexpr std::size_t kLanes = BatchD::size;
static_assert(kColumnPad % kLanes == 0, "columns must pad to whole SIMD batches");
}  // namespace gf

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace gf {

// Hardware gathers of doubles by 32-bit indices read from memory (kLanes of them, any alignment). xsimd 8.1 emulates gathers lane by lane through a function call; the intrinsic is
// several times faster.
inline BatchD gather32(const double* base, const std::int32_t* idx) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  return _mm512_i32gather_pd(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx)), base, 8);
#elif defined(__AVX2__)
  return _mm256_i32gather_pd(base, _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx)), 8);
#else
  alignas(64) double lanes[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) lanes[l] = base[idx[l]];
  return BatchD::load_aligned(lanes);
#endif
}

// Bit l set when lane l of `b` is true.
inline std::uint32_t lane_bits(const xsimd::batch_bool<double, SimdArch>& b) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  return static_cast<std::uint32_t>(static_cast<__mmask8>(b));
#elif defined(__AVX2__)
  return static_cast<std::uint32_t>(_mm256_movemask_pd(static_cast<__m256d>(b)));
#else
  alignas(64) bool lanes[kLanes];
  b.store_aligned(lanes);
  std::uint32_t bits = 0;
  for (std::size_t l = 0; l < kLanes; ++l) bits |= static_cast<std::uint32_t>(lanes[l]) << l;
  return bits;
#endif
}

// The same, where a negative index gives 0.0 (a missing entry) and reads nothing.
inline BatchD gather32_or_zero(const double* base, const std::int32_t* idx) {
#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  const __m256i i = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx));
  const __mmask8 m = _mm256_cmpge_epi32_mask(i, _mm256_setzero_si256());
  return _mm512_mask_i32gather_pd(_mm512_setzero_pd(), m, i, base, 8);
#elif defined(__AVX2__)
  const __m128i i = _mm_loadu_si128(reinterpret_cast<const __m128i*>(idx));
  const __m256d m = _mm256_castsi256_pd(_mm256_cvtepi32_epi64(_mm_cmpgt_epi32(i, _mm_set1_epi32(-1))));
  return _mm256_mask_i32gather_pd(_mm256_setzero_pd(), base, i, m, 8);
#else
  alignas(64) double lanes[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) lanes[l] = idx[l] >= 0 ? base[idx[l]] : 0.0;
  return BatchD::load_aligned(lanes);
#endif
}

// kLanes values base[idx[l]] where every idx[l] lies in [idx[0], idx[0] + kLanes) (the owners of a
// batch of pairs in owner order are a few adjacent rows): one unaligned load of that window and a
// lane permute instead of a gather. row_window checks the lanes once per batch; load_rows falls
// back to a gather when they spread wider, or when the window would pass `rows` (the columns'
// allocated length).
struct RowWindow {
  const std::int32_t* idx = nullptr;
  std::int32_t first = 0;
  bool fits = false;
#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  __m512i perm{};
#endif
};

inline RowWindow row_window(const std::int32_t* idx, std::size_t rows) {
  RowWindow w;
  w.idx = idx;
  w.first = idx[0];
#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  // Every lane within [first, first + kLanes) (unsigned: below first wraps high), so padding lanes
  // or an unsorted batch fall back to the gather.
  const __m256i rel =
      _mm256_sub_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx)), _mm256_set1_epi32(idx[0]));
  w.fits = _mm256_cmplt_epu32_mask(rel, _mm256_set1_epi32(static_cast<int>(kLanes))) == 0xff &&
           static_cast<std::size_t>(idx[0]) + kLanes <= rows;
  if (w.fits) w.perm = _mm512_cvtepi32_epi64(rel);
#else
  (void)rows;
#endif
  return w;
}

inline BatchD load_rows(const double* base, const RowWindow& w) {
#if defined(__AVX512F__) && defined(__AVX512VL__) && !defined(GRAINFLOW_SIMD_256)
  if (w.fits) return _mm512_permutexvar_pd(w.perm, _mm512_loadu_pd(base + w.first));
#endif
  return gather32(base, w.idx);
}

// A table of at most kLanes doubles held in a register: each lane looks its entry up by index
// with one permute (AVX-512) instead of a gather. Indices must be in [0, size).
class RegisterTable {
 public:
  static constexpr std::size_t capacity = kLanes;
  RegisterTable() = default;
  RegisterTable(const double* values, std::size_t n) {
    alignas(64) double v[kLanes] = {};
    for (std::size_t k = 0; k < n && k < kLanes; ++k) v[k] = values[k];
    for (std::size_t k = 0; k < kLanes; ++k) v_[k] = v[k];
    table_ = BatchD::load_aligned(v);
  }
  BatchD lookup(const std::int32_t* idx) const {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
    return _mm512_permutexvar_pd(_mm512_cvtepi32_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(idx))),
                                 table_);
#else
    return gather32(v_, idx);
#endif
  }

 private:
  BatchD table_ = BatchD(0.0);
  alignas(64) double v_[kLanes] = {};
};

}  // namespace gf
