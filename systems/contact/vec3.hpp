// Minimal 3-vector over a scalar or an xsimd batch, for contact laws written once for both.
#pragma once

#include <cmath>

#include "engine/simd.hpp"

namespace gf {

template <class T>
struct V3 {
  T x, y, z;
};

template <class T>
inline V3<T> operator+(const V3<T>& a, const V3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline V3<T> operator-(const V3<T>& a, const V3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline V3<T> operator-(const V3<T>& a) {
  return {-a.x, -a.y, -a.z};
}
template <class T>
inline V3<T> operator*(const T& s, const V3<T>& a) {
  return {s * a.x, s * a.y, s * a.z};
}
template <class T>
inline T dot(const V3<T>& a, const V3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
inline V3<T> cross(const V3<T>& a, const V3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

// Branch-free selection that reads the same for double and for batches.
inline double choose(bool c, double a, double b) { return c ? a : b; }
template <class A>
inline xsimd::batch<double, A> choose(const xsimd::batch_bool<double, A>& c, const xsimd::batch<double, A>& a,
                                      const xsimd::batch<double, A>& b) {
  return xsimd::select(c, a, b);
}
template <class T, class C>
inline V3<T> choose(const C& c, const V3<T>& a, const V3<T>& b) {
  return {choose(c, a.x, b.x), choose(c, a.y, b.y), choose(c, a.z, b.z)};
}
// Both masks (a lane, or the scalar, set in each).
inline bool both(bool a, bool b) { return a && b; }
template <class A>
inline xsimd::batch_bool<double, A> both(const xsimd::batch_bool<double, A>& a, const xsimd::batch_bool<double, A>& b) {
  return a & b;
}
inline double exp_of(double v) { return std::exp(v); }
template <class A>
inline xsimd::batch<double, A> exp_of(const xsimd::batch<double, A>& v) {
  return xsimd::exp(v);
}
inline double sqrt_of(double v) { return std::sqrt(v); }
template <class A>
inline xsimd::batch<double, A> sqrt_of(const xsimd::batch<double, A>& v) {
  return xsimd::sqrt(v);
}

// 1 / sqrt(v) for v > 0. For doubles, the correctly rounded square root and division (the
// reference). For batches on AVX-512, the 14-bit hardware estimate refined by two Newton steps
// (14 -> 28 -> 53 bits; within a few ulp of the reference), a few multiplies instead of a square
// root and a division, which are the slowest instructions of a contact law. v = 0 gives a
// non-finite lane: callers select it away.
inline double rsqrt_of(double v) { return 1.0 / std::sqrt(v); }
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
