// The history-spring pieces that the laws share: turning a spring into the current tangent plane,
// and the slider that caps a spring-dashpot force (Cundall-Strack).
#pragma once

#include "systems/contact/vec3_batch.hpp"

namespace gf {

// The spring projected on the plane normal to n, keeping its length (the contact frame turns;
// the spring turns with it). A spring with no component left in the plane stays as projected.
template <class T>
[[gnu::always_inline]] inline V3<T> turn_spring(const V3<T>& spring, const V3<T>& n) {
  const T tiny(1e-300);
  const T old_len2 = dot(spring, spring);
  const V3<T> d = spring - dot(spring, n) * n;
  const T new_len2 = dot(d, d);
  const auto turned = new_len2 > tiny;
  const T keep = choose(turned, sqrt_of(old_len2) * rsqrt_of(choose(turned, new_len2, T(1.0))), T(1.0));
  return keep * d;
}

// The slider of a spring-dashpot pair: where |f| exceeds the cap, f points along -spring with
// the cap's magnitude (along f itself when the spring has no direction), and the spring is
// shortened to cap / k so that a reversal starts from the cap.
// (A spring counts as having a direction when |spring|^2 > 1e-300, i.e. longer than 1e-150 m.)
template <class T>
[[gnu::always_inline]] inline void slide(V3<T>& f, V3<T>& spring, const T& cap, const T& k) {
  const T f2 = dot(f, f);
  const T len2 = dot(spring, spring);
  const auto over = f2 > cap * cap;
  const auto has_dir = len2 > T(1e-300);
  const T inv = rsqrt_of(choose(has_dir, len2, T(1.0)));
  const T inv_f = rsqrt_of(choose(f2 > T(1e-300), f2, T(1.0)));
  const V3<T> f_capped = choose(has_dir, (-cap * inv) * spring, (cap * inv_f) * f);
  const T k_safe = choose(k > T(0.0), k, T(1.0));
  const V3<T> spring_capped = choose(has_dir, (cap / k_safe * inv) * spring, spring);
  f = choose(over, f_capped, f);
  spring = choose(over, spring_capped, spring);
}

inline double abs_of(double v) { return v < 0 ? -v : v; }
template <class A>
inline xsimd::batch<double, A> abs_of(const xsimd::batch<double, A>& v) {
  return xsimd::abs(v);
}

}  // namespace gf
