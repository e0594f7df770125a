// The one place xsimd is included. GCC 12 reports a false -Wuninitialized inside avx512fintrin.h
// when kernels are instantiated on AVX-512 batches (GCC bug 105593); the diagnostic state is taken
// at the header's own lines, so silencing it around this first inclusion is enough.
#pragma once

#include <cstddef>
#include <cstdint>

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
using BatchI = xsimd::batch<std::int64_t, SimdArch>;
inline constexpr std::size_t kLanes = BatchD::size;
}  // namespace gf

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace gf {

// Hardware gathers and scatters of doubles by 64-bit indices. xsimd 8.1 emulates these lane by
// lane through a function call for 64-bit indices; the intrinsics are several times faster.
inline BatchD gather(const double* base, const BatchI& idx) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  return _mm512_i64gather_pd(idx, base, 8);
#elif defined(__AVX2__)
  return _mm256_i64gather_pd(base, idx, 8);
#else
  return BatchD::gather(base, idx);
#endif
}

// The same with 32-bit indices read from memory (kLanes of them): half the index traffic.
inline BatchD gather32(const double* base, const std::int32_t* idx) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  return _mm512_i32gather_pd(_mm256_load_si256(reinterpret_cast<const __m256i*>(idx)), base, 8);
#elif defined(__AVX2__)
  return _mm256_i32gather_pd(base, _mm_load_si128(reinterpret_cast<const __m128i*>(idx)), 8);
#else
  alignas(64) std::int64_t wide[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) wide[l] = idx[l];
  return BatchD::gather(base, BatchI::load_aligned(wide));
#endif
}

inline void scatter32(const BatchD& v, double* base, const std::int32_t* idx) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  _mm512_i32scatter_pd(base, _mm256_load_si256(reinterpret_cast<const __m256i*>(idx)), v, 8);
#else
  alignas(64) double lanes[kLanes];
  v.store_aligned(lanes);
  for (std::size_t l = 0; l < kLanes; ++l) base[idx[l]] = lanes[l];
#endif
}

inline void scatter(const BatchD& v, double* base, const BatchI& idx) {
#if defined(__AVX512F__) && defined(GRAINFLOW_SIMD_256)
  _mm256_i64scatter_pd(base, idx, v, 8);
#elif defined(__AVX512F__)
  _mm512_i64scatter_pd(base, idx, v, 8);
#else
  v.scatter(base, idx);
#endif
}

}  // namespace gf
