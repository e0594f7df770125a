// The compiler's vector intrinsics, included with GCC 12's false -Wuninitialized inside
// avx512fintrin.h silenced (GCC bug 105593: it fires where kernels are inlined on AVX-512 batches).
// The diagnostic state is taken at the header's own lines, so its first inclusion in a file decides:
// engine/column.hpp includes this header, which puts it ahead of oneTBB's and Eigen's inclusions of
// the same intrinsics in every file that holds a column, and engine/simd.hpp includes it before xsimd.
#pragma once

#if defined(__x86_64__) || defined(__i386__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
