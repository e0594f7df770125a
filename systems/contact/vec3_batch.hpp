// The xsimd batches' overloads of the functions systems/contact/vec3.hpp gives for doubles, so a
// contact law written once runs on both. A law's header includes this one: the overloads must be
// declared before the law's template, since name lookup for its unqualified calls does not search gf
// for xsimd arguments.
#pragma once

#include "engine/simd.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

template <class A>
inline xsimd::batch<double, A> choose(const xsimd::batch_bool<double, A>& c, const xsimd::batch<double, A>& a,
                                      const xsimd::batch<double, A>& b) {
  return xsimd::select(c, a, b);
}
// A vector's selection, lane by lane or for doubles; after the batches' overload, which it calls.
template <class T, class C>
inline V3<T> choose(const C& c, const V3<T>& a, const V3<T>& b) {
  return {choose(c, a.x, b.x), choose(c, a.y, b.y), choose(c, a.z, b.z)};
}
template <class A>
inline xsimd::batch_bool<double, A> both(const xsimd::batch_bool<double, A>& a, const xsimd::batch_bool<double, A>& b) {
  return a & b;
}
template <class A>
inline xsimd::batch<double, A> exp_of(const xsimd::batch<double, A>& v) {
  return xsimd::exp(v);
}
template <class A>
inline xsimd::batch<double, A> sqrt_of(const xsimd::batch<double, A>& v) {
  return xsimd::sqrt(v);
}

// 1 / sqrt(v) for v > 0. For batches on AVX-512, the 14-bit hardware estimate refined by two Newton steps
// (14 -> 28 -> 53 bits; within a few ulp of the reference), a few multiplies instead of a square
// root and a division, which are the slowest instructions of a contact law. v = 0 gives a
// non-finite lane: callers select it away.
template <class A>
inline xsimd::batch<double, A> rsqrt_of(const xsimd::batch<double, A>& v) {
  using B = xsimd::batch<double, A>;
#if defined(__AVX512F__) && !defined(GRAINFLOW_SIMD_256)
  if constexpr (B::size == 8) {
    const B half_v = B(0.5) * v;
    B y = _mm512_rsqrt14_pd(v);
    y = y * (B(1.5) - half_v * y * y);
    return y * (B(1.5) - half_v * y * y);
  }
#endif
  return B(1.0) / xsimd::sqrt(v);
}

}  // namespace gf
