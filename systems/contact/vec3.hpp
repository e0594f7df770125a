// Minimal 3-vector over a scalar or an xsimd batch, for contact laws written once for both. This
// header holds the vector and the scalar functions and includes no xsimd: geometry and outputs use it
// without the vector headers' compile time.
#pragma once

#include <cmath>

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

// Branch-free selection and the few maths functions a contact law calls, for doubles; the xsimd
// batches' overloads are in systems/contact/vec3_batch.hpp, which the laws include.
inline double choose(bool c, double a, double b) { return c ? a : b; }
// Both masks (a lane, or the scalar, set in each).
inline bool both(bool a, bool b) { return a && b; }
inline double exp_of(double v) { return std::exp(v); }
inline double sqrt_of(double v) { return std::sqrt(v); }
// 1 / sqrt(v) for v > 0: the correctly rounded square root and division (the reference).
inline double rsqrt_of(double v) { return 1.0 / std::sqrt(v); }

}  // namespace gf
