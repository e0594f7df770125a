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
//
// Scene: [contact] model = "linear_spring_dashpot", kn, kt (N/m), kr (N m/rad), en, et, er
// (restitution), friction (f_s), rolling_friction (f_r, m), per species pair and against walls.
// Damping from restitution with the effective mass of each term (Table 2):
//   eta = 2 sqrt(m k) ln(1/e) / sqrt(pi^2 + ln^2(1/e))   (e > 0),   eta = 2 sqrt(m k)   (e = 0)
// normal m = m_i m_j/(m_i+m_j), tangential 2/7 of that, rolling I = I_i I_j/(I_i+I_j); against a
// wall the particle's own m_i and I_i. Time-step terms: the damped collision period of each term,
// T = 2 sqrt(pi^2 + ln^2 e) sqrt(m/k) (Table 3).
#pragma once

#include <cmath>
#include <numbers>

#include "engine/field_table.hpp"
#include "engine/scene.hpp"
#include "systems/contact/contact_law.hpp"
#include "systems/contact/size_scaling.hpp"
#include "systems/contact/tangential_spring.hpp"
#include "systems/contact/vec3_batch.hpp"

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

inline double damping_coefficient(double m_eff, double k, double e) {
  if (e <= 0.0) return 2.0 * std::sqrt(m_eff * k);
  const double l = std::log(1.0 / e);
  return 2.0 * std::sqrt(m_eff * k) * l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

// Period of the damped contact oscillation, T = 2 sqrt(pi^2 + ln^2 e) sqrt(m/k) (Table 3).
inline double collision_period(double m_eff, double k, double e) {
  const double l = e > 0.0 ? std::log(e) : 0.0;  // e = 0 is critically damped; use the undamped bound
  return 2.0 * std::sqrt(std::numbers::pi * std::numbers::pi + l * l) * std::sqrt(m_eff / k);
}

// The law's keys in [contact]; [contact.wall] and [[contact.pair]] take the same keys, each defaulting
// to the [contact] value.
inline constexpr Field kLinearSpringDashpotRows[] = {
    {"kn", "N/m", range::stiffness, "", kNoDefault, "", "normal spring"},
    {"kt", "N/m", range::stiffness_or_zero, "", kNoDefault, "", "tangential spring"},
    {"en", "", kFraction, "", kNoDefault, "", "normal restitution"},
    {"et", "", kFraction, "", kNoDefault, "", "tangential restitution"},
    {"friction", "", range::coefficient, "", kNoDefault, "",
     "sliding friction coefficient f_s: the tangential force is capped at f_s times the normal force"},
    {"kr", "N m/rad", range::torsion_or_zero, "", 0.0, "", "rolling spring (0: none)"},
    {"er", "", kFraction, "", kNoDefault, "`en`", "rolling restitution"},
    {"rolling_friction", "m", range::length_or_zero, "", 0.0, "",
     "f_r: the rolling torque is capped at f_r times the normal force"},
};
inline constexpr FieldTable kLinearSpringDashpotFields{"[contact] model = \"linear_spring_dashpot\"", "scene-files.md",
                                                       kLinearSpringDashpotRows};

struct LinearSpringDashpot {
  static constexpr const FieldTable* fields = &kLinearSpringDashpotFields;
  static constexpr std::string_view name = "linear_spring_dashpot";
  static constexpr std::string_view title = "linear spring-dashpot-slider (seed 000 Table 1)";

  // Species state nothing beyond diameter and density for this law.
  struct Material {};
  static Material read_material(const SceneNode&) { return {}; }

  // What a scene states for one pair of species (or species and wall).
  struct Params {
    double kn = 0;  // N/m, normal spring
    double kt = 0;  // N/m, tangential spring
    double kr = 0;  // N m/rad, rolling spring
    double en = 1;  // normal restitution, [0, 1]
    double et = 1;  // tangential restitution
    double er = 1;  // rolling restitution
    double friction = 0;          // sliding friction coefficient f_s
    double rolling_friction = 0;  // f_r, m (rolling torque cap f_r |F_n|)
  };
  // `base` is the [contact] table's values when reading an override ([contact.wall], [[contact.pair]]).
  static Params read_params(const SceneNode& node, const Params* base, bool /*wall*/) {
    const FieldTable& t = *fields;
    auto num = [&](std::string_view key, const double* inherited) {
      return read_number(node, t.field(key), inherited);
    };
    Params p;
    p.kn = num("kn", base ? &base->kn : nullptr);
    p.kt = num("kt", base ? &base->kt : nullptr);
    p.en = num("en", base ? &base->en : nullptr);
    p.et = num("et", base ? &base->et : nullptr);
    p.friction = num("friction", base ? &base->friction : nullptr);
    p.kr = num("kr", base ? &base->kr : nullptr);
    p.er = read_number(node, t.field("er"), base ? &base->er : &p.en);
    p.rolling_friction = num("rolling_friction", base ? &base->rolling_friction : nullptr);
    return p;
  }

  // Per type-pair constants, in this order.
  enum Constant : std::size_t { kKn, kKt, kKr, kEtaN, kEtaT, kEtaR, kFs, kFr, kConstants };
  static constexpr std::array<std::string_view, kConstants> constant_names = {"kn",    "kt",    "kr", "eta_n",
                                                                              "eta_t", "eta_r", "fs", "fr"};
  // Effective mass and inertia of a pair: the reduced ones, or the particle's own against a wall.
  static double reduced(double a, double b, bool b_wall) { return b_wall ? a : a * b / (a + b); }
  static std::array<double, kConstants> constants(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                                  const Params& p) {
    const double m = reduced(a.mass, b.mass, b.wall), i = reduced(a.inertia, b.inertia, b.wall);
    return {p.kn,
            p.kt,
            p.kr,
            damping_coefficient(m, p.kn, p.en),
            damping_coefficient(2.0 / 7.0 * m, p.kt, p.et),
            p.kr > 0.0 ? damping_coefficient(i, p.kr, p.er) : 0.0,
            p.friction,
            p.rolling_friction};
  }
  static std::vector<StepTerm> critical_terms(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                              const Params& p) {
    const double m = reduced(a.mass, b.mass, b.wall), i = reduced(a.inertia, b.inertia, b.wall);
    std::vector<StepTerm> t;
    if (p.kn > 0) t.push_back({collision_period(m, p.kn, p.en), "normal"});
    if (p.kt > 0) t.push_back({collision_period(2.0 / 7.0 * m, p.kt, p.et), "tangential"});
    if (p.kr > 0) t.push_back({collision_period(i, p.kr, p.er), "rolling"});
    return t;
  }

  // Grains of a size distribution (size_scaling.hpp): each damping coefficient is sqrt(m k) times a
  // factor of e, so it scales with the square root of the effective mass (inertia for rolling).
  template <class T>
  [[gnu::always_inline]] static void resize(std::array<T, kConstants>& k, const SizeRatio<T>& q) {
    const T sm = sqrt_of(q.m);
    k[kEtaN] = k[kEtaN] * sm;
    k[kEtaT] = k[kEtaT] * sm;
    k[kEtaR] = k[kEtaR] * sqrt_of(q.inertia);
  }

  // History: the tangential spring d_t (m) and the rolling angle a (rad), seen from row i.
  static constexpr std::size_t kHistory = 6;
  static HistoryLayout history() {
    return {"linear_spring_dashpot.springs", {"shear.x", "shear.y", "shear.z", "roll.x", "roll.y", "roll.z"}};
  }

  // The pipeline's form: geometry, constants and history as the drivers hold them.
  template <class T, class M>
  [[gnu::always_inline]] static ContactForce<T> evaluate(const M& touching, const ContactGeometry<T>& g,
                                  const std::array<T, kConstants>& k, const T& dt, std::array<T, kHistory>& h) {
    const LsdCoeffs<T> c{k[kKn], k[kKt], k[kKr], k[kEtaN], k[kEtaT], k[kEtaR], k[kFs], k[kFr]};
    LsdState<T> s{{h[0], h[1], h[2]}, {h[3], h[4], h[5]}};
    const LsdResult<T> r = evaluate(touching, g.n, g.delta, g.v, g.w, c, dt, s);
    h = {s.shear.x, s.shear.y, s.shear.z, s.roll.x, s.roll.y, s.roll.z};
    return {r.force, r.force_t, r.rolling_torque, -r.rolling_torque};
  }

  // `touching` masks lanes (or the scalar) in contact; elsewhere springs reset and forces vanish.
  template <class T, class M>
  [[gnu::always_inline]] static LsdResult<T> evaluate(const M& touching, const V3<T>& n, const T& delta, const V3<T>& v, const V3<T>& w,
                               const LsdCoeffs<T>& c, const T& dt, LsdState<T>& s) {
    const T zero(0.0);
    const T vn = dot(v, n);
    const V3<T> vt = v - vn * n;
    const T fn_signed = -c.kn * delta - c.eta_n * vn;  // along n
    const V3<T> fnv = fn_signed * n;
    const T fn_mag = abs_of(fn_signed);

    V3<T> d = turn_spring(s.shear, n);
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

};

}  // namespace gf
