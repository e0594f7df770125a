// Representative-volume ("coarse grain") contact law, seed 004 (Cherpitskiy, Korolev, Tarshis,
// ChemChemTech 2022; the readable form in ../shared/spec/004-coarse-grained-mixer.md). A model
// particle stands for many real grains of one component and only translates (no rotation). For
// model particles i, j with d = |r_j - r_i|, n the unit vector from i towards j, v = v_i - v_j,
// m* = m_i m_j/(m_i + m_j), R* = R_i R_j/(R_i + R_j), |g| the scene's gravity magnitude and the
// overlap delta = R_i + R_j - d (negative apart):
//   amplitude   A = exp(delta / (k_d R*))          1 at touching, grows with overlap, decays apart
//   cut-off     a = (A - A_c) / (1 - A_c) for delta > -reach, 0 beyond;  reach = k_d R* ln(1/A_c)   (m)
//   normal      F_n = -(|g| m* a + [v.n > 0] min(k_r |g| m* a, m* v.n/dt)) n                      (N)
//   friction    F_t = -|g| m* a k_p (tau - n (n.tau)),  tau = v / sqrt(|v|^2 + v_e^2)              (N)
// Against a wall: R* -> R_i, m* -> m_i, (k_d, k_r, k_p) -> the wall's (k_d^u, k_r^u, k_p^u), and v the
// velocity of i relative to the wall's closest point (omega x r for a turning wall; wall_contact.cpp).
//
// Choices, each tested in tests/representative_volume_test.cpp:
// - The force acts before touching, out to the reach: the law declares kReach (contact_law.hpp), so
//   the neighbour search looks that much further and the drivers hand it pairs with a negative overlap.
// - Inelastic repulsion: the OCR reads the approach factor as (1 - k_r), which with k_r = 15 would
//   attract; the dissipative reading is used, approach (v.n > 0) (1 + k_r) times separation. A head-on
//   collision then keeps e = (1 + k_r)^(-1/2) of the normal speed, losing more the larger k_r.
//   The switch is a step in v.n: at rest the surplus k_r |g| m* a of the slightest approach would
//   overshoot every step, throwing a resting particle off its support with a normal speed of about
//   k_r |g| dt and its friction with it (uncapped, a particle on a 3 degree slope, inside the friction
//   angle, slid away, and the box scene's bed stood 1.5 times higher). So the surplus is capped at
//   m* v.n/dt, the force that just stops the approach within the step: a collision faster than
//   k_r |g| a dt (0.015 m/s at dt = 1e-4 s) is unchanged except in its last step before turning.
// - The cut-off: the exponential never vanishes, so the amplitude is shifted to reach zero at
//   A = A_c (cutoff, default 1e-3) and is zero beyond: the force is continuous there, exactly zero past
//   it, and still exactly |g| m* at touching ((1 - A_c)/(1 - A_c) = 1), a pair at rest in contact
//   carrying one weight. It differs from the bare exponential by A_c (1 - A)/(1 - A_c) of |g| m*.
// - tau = v/|v| (the paper's, slip_speed v_e = 0) flips the friction's sign every step when the slip
//   is about zero (a grain at rest on a slope chatters with a speed of about |g| k_p dt); with v_e > 0
//   the friction is viscous below v_e, with the relaxation time v_e / (|g| k_p a): at rest on a slope
//   within the friction angle the grain creeps at v_e tan(theta)/sqrt(k_p^2 - tan^2(theta)) instead.
//
// Published coefficients (the defaults): particles k_d = 0.25, k_r = 15, k_p = 0.15; walls
// k_d^u = 0.2, k_r^u = 10, k_p^u = 0.1.
// Time-step terms: the period 2 pi sqrt(m*/k) of the approach stiffness at touching,
// k = |g| m* (1 + k_r)/((1 - A_c) k_d R*), which a load of N weights (A = N) shortens by sqrt(N), so
// the default dt_safety of 0.1 leaves room for piles about ten particles deep; and, for v_e > 0, the
// friction's relaxation time at touching v_e/(|g| k_p): a longer step chatters again.
//
// Scene: [contact] model = "representative_volume", kd, kr, kp (between particles), cutoff (A_c),
// slip_speed (v_e, m/s); [contact.wall] kd, kr, kp (the wall's, defaults the published wall values,
// not [contact]'s), cutoff, slip_speed; [[contact.pair]] any of them for one pair of species. Every
// species must have rotates = false; gravity must not be zero (|g| sets the force scale).
// Written once for double and for xsimd batches; branches are selections.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "engine/field_table.hpp"
#include "engine/scene.hpp"
#include "systems/contact/contact_law.hpp"
#include "systems/contact/vec3_batch.hpp"

namespace gf {

// The law's keys in [contact]; [[contact.pair]] takes the same keys, each defaulting to the [contact]
// value. [contact.wall] has its own coefficients, whose defaults are the published wall values, not
// [contact]'s.
inline constexpr Field kRepresentativeVolumeRows[] = {
    {"kd", "", range::positive_factor, "", 0.25, "", "decay length k_d of the force amplitude, in units of R*"},
    {"kr", "", range::coefficient, "", 15.0, "",
     "approach factor k_r: the approach force is (1 + k_r) times the separation force"},
    {"kp", "", range::coefficient, "", 0.15, "", "friction coefficient k_p"},
    {"cutoff", "", {0, 0.5, true, false}, "", 0.001, "", "the amplitude A_c below which no force acts"},
    {"slip_speed", "m/s", range::speed_or_zero, "", 0.01, "",
     "friction regularisation v_e (0: the unit vector of the published law)"},
};
inline constexpr FieldTable kRepresentativeVolumeFields{"[contact] model = \"representative_volume\"", "scene-files.md",
                                                        kRepresentativeVolumeRows};
inline constexpr Field kRepresentativeVolumeWallRows[] = {
    {"kd", "", range::positive_factor, "", 0.2, "", "the wall's k_d^u"},
    {"kr", "", range::coefficient, "", 10.0, "", "the wall's approach factor k_r^u"},
    {"kp", "", range::coefficient, "", 0.1, "", "the wall's friction k_p^u"},
    {"cutoff", "", {0, 0.5, true, false}, "", kNoDefault, "`[contact]`'s", "as in `[contact]`"},
    {"slip_speed", "m/s", range::speed_or_zero, "", kNoDefault, "`[contact]`'s", "as in `[contact]`"},
};
inline constexpr FieldTable kRepresentativeVolumeWallFields{"[contact.wall] model = \"representative_volume\"",
                                                            "scene-files.md", kRepresentativeVolumeWallRows};

struct RepresentativeVolume {
  static constexpr const FieldTable* fields = &kRepresentativeVolumeFields;
  static constexpr const FieldTable* wall_fields = &kRepresentativeVolumeWallFields;
  static constexpr std::string_view name = "representative_volume";
  static constexpr std::string_view title = "representative volumes, no rotation (seed 004)";

  // Species state nothing beyond diameter and density for this law.
  struct Material {};
  static Material read_material(const SceneNode&) { return {}; }

  struct Coefficients {
    double kd;  // decay length of the amplitude in units of R* (k_d)
    double kr;  // approach factor (k_r): approach force (1 + k_r) times the separation force
    double kp;  // friction (k_p)
  };
  struct Params {
    // The published values, as the key tables give them: between model particles, and against walls
    // (k_d^u, k_r^u, k_p^u).
    Coefficients pair{kRepresentativeVolumeRows[0].fallback, kRepresentativeVolumeRows[1].fallback,
                      kRepresentativeVolumeRows[2].fallback};
    Coefficients wall{kRepresentativeVolumeWallRows[0].fallback, kRepresentativeVolumeWallRows[1].fallback,
                      kRepresentativeVolumeWallRows[2].fallback};
    double cutoff = kRepresentativeVolumeRows[3].fallback;      // A_c: the amplitude below which nothing acts
    double slip_speed = kRepresentativeVolumeRows[4].fallback;  // v_e, m/s: friction regularisation (0: the paper's unit vector)
  };
  // `base`: the [contact] values when reading [contact.wall] (wall: its coefficients) or [[contact.pair]].
  // The coefficients not given take the table's defaults ([contact] and [contact.wall]) or the
  // [contact] values ([[contact.pair]]).
  static Params read_params(const SceneNode& node, const Params* base, bool wall) {
    Params p = base ? *base : Params{};
    const FieldTable& t = wall ? *wall_fields : *fields;
    Coefficients& c = wall ? p.wall : p.pair;
    c = read_coefficients(node, t, base && !wall ? &c : nullptr);
    p.cutoff = read_number(node, t.field("cutoff"), base ? &base->cutoff : nullptr);
    p.slip_speed = read_number(node, t.field("slip_speed"), base ? &base->slip_speed : nullptr);
    return p;
  }
  static Coefficients read_coefficients(const SceneNode& node, const FieldTable& t, const Coefficients* inherited) {
    return {read_number(node, t.field("kd"), inherited ? &inherited->kd : nullptr),
            read_number(node, t.field("kr"), inherited ? &inherited->kr : nullptr),
            read_number(node, t.field("kp"), inherited ? &inherited->kp : nullptr)};
  }

  // What else the scene must be: model particles do not rotate, and |g| sets the force scale.
  static void check_scene(const SceneNode& root, double gravity) {
    const std::string fix_law = "use model = \"linear_spring_dashpot\" or \"hertz_mindlin\"";
    if (root.has("bodies") || root.has("shape"))
      root.table("contact").fail("model", "the representative-volume law acts between spherical model particles, "
                                          "not composite bodies ([[bodies]])",
                                 fix_law + " for composite bodies");
    if (root.has("periodic"))
      root.fail("periodic", "periodic faces are not yet made for a law that acts beyond touching",
                "remove [periodic], or " + fix_law);
    for (const SceneNode& sp : root.tables("species"))
      if (sp.get_bool("rotates", true))
        sp.fail("rotates", "a representative volume only translates (seed 004 has no angular velocity)",
                "set rotates = false in every [[species]]");
    if (!(gravity > 0.0))
      root.table("run").fail("gravity", "the representative-volume law's forces are multiples of |g| m, so zero "
                                        "gravity gives no force at all",
                             "give a non-zero gravity (m/s^2), e.g. [0, -9.81, 0]");
  }

  enum Constant : std::size_t { kWeight, kMass, kInvDecay, kCut, kKr, kKp, kSlip2, kReachLength, kConstants };
  static constexpr std::array<std::string_view, kConstants> constant_names = {
      "|g| m*", "m*", "1/(k_d R*)", "A_c", "k_r", "k_p", "v_e^2", "reach k_d R* ln(1/A_c)"};

  struct Pair {
    double m, r;  // m*, R* (the particle's own against a wall)
    Coefficients c;
  };
  static Pair pair_of(const ContactBody<Material>& a, const ContactBody<Material>& b, const Params& p) {
    if (b.wall) return {a.mass, a.radius, p.wall};
    return {a.mass * b.mass / (a.mass + b.mass), a.radius * b.radius / (a.radius + b.radius), p.pair};
  }
  static std::array<double, kConstants> constants(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                                  const Params& p) {
    const Pair x = pair_of(a, b, p);
    const double decay = x.c.kd * x.r;  // m
    return {a.gravity * x.m,
            x.m,
            1.0 / decay,
            p.cutoff,
            x.c.kr,
            x.c.kp,
            p.slip_speed * p.slip_speed,
            decay * std::log(1.0 / p.cutoff)};
  }
  static std::vector<StepTerm> critical_terms(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                              const Params& p) {
    const Pair x = pair_of(a, b, p);
    const double g = a.gravity;
    std::vector<StepTerm> t;
    if (!(g > 0.0)) return t;
    t.push_back({2.0 * std::numbers::pi * std::sqrt((1.0 - p.cutoff) * x.c.kd * x.r / (g * (1.0 + x.c.kr))),
                 "normal, approaching at touching"});
    if (p.slip_speed > 0.0 && x.c.kp > 0.0) t.push_back({p.slip_speed / (g * x.c.kp), "friction below slip_speed"});
    return t;
  }

  // No history: the force depends on the present geometry and velocities only.
  static constexpr std::size_t kHistory = 0;
  static HistoryLayout history() { return {"representative_volume", {}, true}; }

  // Acts before touching: the index of the constant that holds the reach (contact_law.hpp).
  static constexpr std::size_t kReach = kReachLength;

  // `touching` masks the lanes the driver hands over (within r_i + r_j + reach); the law itself
  // zeroes every lane past the cut-off, so the force beyond it is exactly zero whatever the driver.
  template <class T, class M>
  [[gnu::always_inline]] static ContactForce<T> evaluate(const M& touching, const ContactGeometry<T>& g,
                                                         const std::array<T, kConstants>& k, const T& dt,
                                                         std::array<T, kHistory>& /*h*/) {
    const T zero(0.0), one(1.0);
    const V3<T>& n = g.n;
    const auto acting = both(touching, g.delta > -k[kReach]);
    const T amp = exp_of(g.delta * k[kInvDecay]);
    const T shifted = (amp - k[kCut]) / (one - k[kCut]);
    const T a = choose(shifted > zero, shifted, zero);
    const T vn = dot(g.v, n);
    const T weight = k[kWeight] * a;
    // The approach surplus k_r |g| m* a, at most m* v_n/dt (what stops the approach within the step).
    const T surplus = k[kKr] * weight, stop = k[kMass] * vn / dt;
    const T fn = weight + choose(vn > zero, choose(stop < surplus, stop, surplus), zero);  // repulsion, -n on i
    // tau - n (n.tau) = v_t / sqrt(|v|^2 + v_e^2); no slip and v_e = 0: no friction.
    const T s2 = dot(g.v, g.v) + k[kSlip2];
    const auto slips = s2 > zero;
    const T inv = choose(slips, rsqrt_of(choose(slips, s2, one)), zero);
    const V3<T> vt = g.v - vn * n;
    const V3<T> ft = (-(weight * k[kKp] * inv)) * vt;
    const V3<T> zv{zero, zero, zero};
    ContactForce<T> r;
    r.force_t = choose(acting, ft, zv);
    r.force = choose(acting, (-fn) * n + ft, zv);
    r.torque_i = zv;
    r.torque_j = zv;
    return r;
  }
};

}  // namespace gf
