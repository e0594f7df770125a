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
// Kernels are compiled for the build machine's widest vectors (-march=native).
using SimdArch = xsimd::default_arch;
using BatchD = xsimd::batch<double, SimdArch>;
using BatchI = xsimd::batch<std::int64_t, SimdArch>;
inline constexpr std::size_t kLanes = BatchD::size;
}  // namespace gf
