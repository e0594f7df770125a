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
    const T keep = choose(new_len2 > tiny, sqrt_of(old_len2 / choose(new_len2 > tiny, new_len2, T(1.0))), T(1.0));
    d = keep * d;
    d = d + dt * vt;
    V3<T> ft = (-c.kt) * d - c.eta_t * vt;
    const T cap_t = c.fs * fn_mag;
    const T ft2 = dot(ft, ft);
    const T d_len = sqrt_of(dot(d, d));
    const auto slip = ft2 > cap_t * cap_t;
    const auto has_d = d_len > T(1e-300);
    const T inv_d = T(1.0) / choose(has_d, d_len, T(1.0));
    const T ft_len = sqrt_of(choose(ft2 > tiny, ft2, T(1.0)));
    // At the cap: along -d_t when the spring has a direction, else along the damping force.
    const V3<T> ft_cap_spring = (-cap_t * inv_d) * d;
    const V3<T> ft_cap_damp = (cap_t / ft_len) * ft;
    const V3<T> ft_capped = choose(has_d, ft_cap_spring, ft_cap_damp);
    const T kt_safe = choose(c.kt > zero, c.kt, T(1.0));
    const V3<T> d_capped = choose(has_d, (cap_t / kt_safe * inv_d) * d, d);
    ft = choose(slip, ft_capped, ft);
    d = choose(slip, d_capped, d);

    // Rolling spring-dashpot-slider on the relative angular velocity.
    V3<T> a = s.roll + dt * w;
    V3<T> tr = (-c.kr) * a - c.eta_r * w;
    const T cap_r = c.fr * fn_mag;
    const T tr2 = dot(tr, tr);
    const T a_len = sqrt_of(dot(a, a));
    const auto roll_slip = tr2 > cap_r * cap_r;
    const auto has_a = a_len > T(1e-300);
    const T inv_a = T(1.0) / choose(has_a, a_len, T(1.0));
    const T tr_len = sqrt_of(choose(tr2 > tiny, tr2, T(1.0)));
    const V3<T> tr_capped = choose(has_a, (-cap_r * inv_a) * a, (cap_r / tr_len) * tr);
    const T kr_safe = choose(c.kr > zero, c.kr, T(1.0));
    const V3<T> a_capped = choose(has_a, (cap_r / kr_safe * inv_a) * a, a);
    tr = choose(roll_slip, tr_capped, tr);
    a = choose(roll_slip, a_capped, a);

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
  static double xsimd_abs(double v) { return v < 0 ? -v : v; }
  template <class A>
  static xsimd::batch<double, A> xsimd_abs(const xsimd::batch<double, A>& v) {
    return xsimd::abs(v);
  }
};

}  // namespace gf
