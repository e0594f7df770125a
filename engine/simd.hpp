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
inline constexpr std::size_t kLanes = BatchD::size;
}  // namespace gf

#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

namespace gf {

// Hardware gathers of doubles by 32-bit indices read from memory (kLanes of them, aligned to the
// batch). xsimd 8.1 emulates gathers lane by lane through a function call; the intrinsic is
// several times faster.
inline BatchD gather32(const double* base, const std::int32_t* idx) {
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  return _mm512_i32gather_pd(_mm256_load_si256(reinterpret_cast<const __m256i*>(idx)), base, 8);
#elif defined(__AVX2__)
  return _mm256_i32gather_pd(base, _mm_load_si128(reinterpret_cast<const __m128i*>(idx)), 8);
#else
  alignas(64) double lanes[kLanes];
  for (std::size_t l = 0; l < kLanes; ++l) lanes[l] = base[idx[l]];
  return BatchD::load_aligned(lanes);
#endif
}

}  // namespace gf
