// Three-equation linear spring-dashpot-slider contact law, seed 000 (Zhao & Cheng 2007, Table 1).
// For sphere i touching j (or a wall), with n the unit vector from i's centre towards the contact,
// delta the overlap (m), v the velocity of i's contact point relative to j's (m/s) and w = w_i - w_j (rad/s):
//   normal      F_n = -k_n delta n - eta_n V_n                       (N)
//   tangential  F_t = -k_t d_t - eta_t V_t,  |F_t| <= f_s |F_n|       (N)   d_t: tangential spring (m)
//   rolling     T_r = -k_r a - eta_r w,      |T_r| <= f_r |F_n|       (N m) a: rolling angle (rad)
// The tangential torque L_i n x F_t is the driver's, since only it knows the lever arm.
// Springs are history: d_t is rotated into the current tangent plane keeping its length, as the
// contact frame turns; at the Coulomb (or rolling) cap the force points along -d_t (-a) as the
// seed writes it, and the spring is shortened to the cap so that reversal starts from the cap
// rather than from an ever-growing spring (Cundall-Strack). The normal force is not clipped at
// zero: the linear dashpot gives exactly the restitution e with contact time T/2 that Table 3 uses.
//
// Written once for double and for xsimd batches; branches are selections.
#pragma once

#include "systems/contact/vec3.hpp"

namespace gf {

template <class T>
struct LsdCoeffs {
  T kn, kt, kr, eta_n, eta_t, eta_r, fs, fr;
};

template <class T>
struct LsdState {
  V3<T> shear;  // tangential spring d_t, m
  V3<T> roll;   // rolling angle a, rad
};

template <class T>
struct LsdResult {
  V3<T> force;         // on i, N (normal + tangential)
  V3<T> force_t;       // tangential part on i, N
  V3<T> rolling_torque;  // on i, N m (on j it is the opposite)
};

struct LinearSpringDashpot {
  // `touching` masks lanes (or the scalar) in contact; elsewhere springs reset and forces vanish.
  template <class T, class M>
  static LsdResult<T> evaluate(const M& touching, const V3<T>& n, const T& delta, const V3<T>& v, const V3<T>& w,
                               const LsdCoeffs<T>& c, const T& dt, LsdState<T>& s) {
    const T zero(0.0);
    const T tiny(1e-300);
    const T vn = dot(v, n);
    const V3<T> vt = v - vn * n;
    const T fn_signed = -c.kn * delta - c.eta_n * vn;  // along n
    const V3<T> fnv = fn_signed * n;
    const T fn_mag = xsimd_abs(fn_signed);

    // Tangential spring: project the old spring on the current tangent plane, keep its length.
    const T old_len2 = dot(s.shear, s.shear);
    V3<T> d = s.shear - dot(s.shear, n) * n;
    const T new_len2 = dot(d, d);
    const auto turned = new_len2 > tiny;
    const T keep = choose(turned, sqrt_of(old_len2) * rsqrt_of(choose(turned, new_len2, T(1.0))), T(1.0));
    d = keep * d;
    d = d + dt * vt;
    V3<T> ft = (-c.kt) * d - c.eta_t * vt;
    slide(ft, d, c.fs * fn_mag, c.kt);

    // Rolling spring-dashpot-slider on the relative angular velocity.
    V3<T> a = s.roll + dt * w;
    V3<T> tr = (-c.kr) * a - c.eta_r * w;
    slide(tr, a, c.fr * fn_mag, c.kr);

    const V3<T> zv{zero, zero, zero};
    s.shear = choose(touching, d, zv);
    s.roll = choose(touching, a, zv);
    LsdResult<T> r;
    r.force_t = choose(touching, ft, zv);
    r.force = choose(touching, fnv + ft, zv);
    r.rolling_torque = choose(touching, tr, zv);
    return r;
  }

 private:
  // The slider of a spring-dashpot pair: where |f| exceeds the cap, f points along -spring with
  // the cap's magnitude (along f itself when the spring has no direction), and the spring is
  // shortened to cap / k so that a reversal starts from the cap.
  // (A spring counts as having a direction when |spring|^2 > 1e-300, i.e. longer than 1e-150 m.)
  template <class T>
  static void slide(V3<T>& f, V3<T>& spring, const T& cap, const T& k) {
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

  static double xsimd_abs(double v) { return v < 0 ? -v : v; }
  template <class A>
  static xsimd::batch<double, A> xsimd_abs(const xsimd::batch<double, A>& v) {
    return xsimd::abs(v);
  }
};

}  // namespace gf
