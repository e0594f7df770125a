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
inline double sqrt_of(double v) { return std::sqrt(v); }
template <class A>
inline xsimd::batch<double, A> sqrt_of(const xsimd::batch<double, A>& v) {
  return xsimd::sqrt(v);
}

}  // namespace gf
