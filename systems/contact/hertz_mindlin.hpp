// Hertz-Mindlin no-slip contact law, seed 001 (Chen Hui et al.; the form used by EDEM and
// LIGGGHTS' hertz/tangential_history). For spheres i, j (or i and a wall) with R* = R_i R_j/(R_i+R_j),
// m* = m_i m_j/(m_i+m_j), 1/E* = (1-nu_i^2)/E_i + (1-nu_j^2)/E_j, 1/G* = 2(2-nu_i)(1+nu_i)/E_i +
// 2(2-nu_j)(1+nu_j)/E_j, beta = ln e / sqrt(ln^2 e + pi^2), alpha the overlap (m), n the unit
// vector from i towards the contact, v the velocity of i's contact point relative to j's:
//   S_n = 2 E* sqrt(R* alpha),  S_t = 8 G* sqrt(R* alpha)                                 (N/m)
//   normal      F_n = -(4/3 E* sqrt(R*) alpha^(3/2) + 2 sqrt(5/6) (-beta) sqrt(S_n m*) v_n) n   (N)
//   tangential  F_t = -S_t d_t - 2 sqrt(5/6) (-beta) sqrt(S_t m*) V_t,  |F_t| <= mu |F_n|      (N)
//   rolling     T_i = -mu_r |F_n| R_i w_hat,  T_j = +mu_r |F_n| R_j w_hat                       (N m)
// d_t is the tangential spring (history, m): the accumulated tangential displacement, turned into
// the current tangent plane, capped at Coulomb's limit like the linear law's (Cundall-Strack).
// Rolling is the constant directional torque of the seed: each sphere's own radius, against the
// relative angular velocity w = w_i - w_j (a sphere on a wall at rest: its own w_i, as the seed
// writes; a sphere turning with a rotating drum wall feels none). The normal force is not clipped
// at zero, as LIGGGHTS does not by default; the restitution is then e to within 0.02 % (checked
// in the tests, Chung & Ooi test 3).
// A wall is rigid unless [contact.wall] gives youngs_modulus and poisson_ratio; R* = R_i, m* = m_i.
//
// Time-step terms: the Rayleigh time of each species, T_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766),
// G = E / (2(1+nu)), and the Hertz contact time t_c = 2.87 (m*^2 / (R* E*^2 v))^(1/5) at the
// scene's impact_speed v (default 1 m/s).
//
// Written once for double and for xsimd batches; branches are selections.
#pragma once

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "engine/field_table.hpp"
#include "engine/scene.hpp"
#include "systems/contact/contact_law.hpp"
#include "systems/contact/size_scaling.hpp"
#include "systems/contact/tangential_spring.hpp"
#include "systems/contact/vec3_batch.hpp"

namespace gf {

// The law's keys in [contact]; [contact.wall] and [[contact.pair]] take the same keys, each defaulting
// to the [contact] value, and [contact.wall] the wall's material besides. A species' material is
// read from its [[species]] table.
inline constexpr Field kHertzMindlinRows[] = {
    {"restitution", "", {0, 1, true, false}, "", kNoDefault, "", "coefficient of restitution e"},
    {"friction", "", range::coefficient, "", kNoDefault, "",
     "sliding friction coefficient μ: the tangential force is capped at μ times the normal force"},
    {"rolling_friction", "", range::coefficient, "", 0.0, "",
     "μ_r: the constant rolling torque μ_r times the normal force times the radius"},
    {"impact_speed", "m/s", range::speed, "", 1.0, "",
     "the speed at which the Hertz contact time of the critical step is computed"},
};
inline constexpr FieldTable kHertzMindlinFields{"[contact] model = \"hertz_mindlin\"", "scene-files.md", kHertzMindlinRows};
inline constexpr Field kHertzMaterialRows[] = {
    {"youngs_modulus", "Pa", range::modulus, "", kNoDefault, "required with `hertz_mindlin`",
     "Young's modulus (read only by the Hertz–Mindlin law)"},
    {"poisson_ratio", "", {-0.99, 0.5, false, false}, "", kNoDefault, "required with `hertz_mindlin`",
     "Poisson's ratio (read only by the Hertz–Mindlin law)"},
};
inline constexpr FieldTable kHertzMaterialFields{"[[species]] material", "", kHertzMaterialRows};
inline constexpr Field kHertzWallRows[] = {
    {"youngs_modulus", "Pa", range::modulus, "", kNoDefault, "rigid wall",
     "the wall's Young's modulus; give it with `poisson_ratio`, or neither for a rigid wall"},
    {"poisson_ratio", "", {-0.99, 0.5, false, false}, "", kNoDefault, "rigid wall",
     "the wall's Poisson's ratio, with `youngs_modulus`"},
};
inline constexpr FieldTable kHertzWallFields{"[contact.wall] model = \"hertz_mindlin\"", "scene-files.md", kHertzWallRows};

struct HertzMindlin {
  static constexpr const FieldTable* fields = &kHertzMindlinFields;
  static constexpr const FieldTable* wall_fields = &kHertzWallFields;
  static constexpr std::string_view name = "hertz_mindlin";
  static constexpr std::string_view title = "Hertz-Mindlin no-slip (seed 001)";

  struct Material {
    double youngs_modulus = std::numeric_limits<double>::infinity();  // Pa (a rigid wall by default)
    double poisson_ratio = 0.0;
  };
  static Material read_material(const SceneNode& species) {
    return {read_number(species, kHertzMaterialFields.field("youngs_modulus")),
            read_number(species, kHertzMaterialFields.field("poisson_ratio"))};
  }

  struct Params {
    double restitution = 1;      // e, (0, 1]
    double friction = 0;         // mu, sliding
    double rolling_friction = 0; // mu_r, dimensionless (torque mu_r |F_n| R)
    double impact_speed = 1;     // m/s, for the Hertz contact time of the critical step
    Material wall;               // the wall's material, in [contact.wall]
  };
  static Params read_params(const SceneNode& node, const Params* base, bool wall) {
    const FieldTable& t = *fields;
    const bool b = base != nullptr;
    Params p;
    // e = 0 would make beta -1 exactly and the damping critical; the model's beta(e) is meant for e > 0.
    p.restitution = read_number(node, t.field("restitution"), b ? &base->restitution : nullptr);
    p.friction = read_number(node, t.field("friction"), b ? &base->friction : nullptr);
    p.rolling_friction = read_number(node, t.field("rolling_friction"), b ? &base->rolling_friction : nullptr);
    p.impact_speed = read_number(node, t.field("impact_speed"), b ? &base->impact_speed : nullptr);
    if (wall) {
      // A rigid wall has no Poisson ratio to give: the two keys come together or not at all.
      if (node.has("youngs_modulus") != node.has("poisson_ratio"))
        node.fail(node.has("youngs_modulus") ? "poisson_ratio" : "youngs_modulus",
                  "a wall's material needs both youngs_modulus and poisson_ratio",
                  "give both (Pa, and a ratio in [-0.99, 0.5]), or neither for a rigid wall");
      if (node.has("youngs_modulus")) {
        p.wall.youngs_modulus = read_number(node, wall_fields->field("youngs_modulus"));
        p.wall.poisson_ratio = read_number(node, wall_fields->field("poisson_ratio"));
      }
    }
    return p;
  }

  enum Constant : std::size_t { kKh, kCn, kSt, kCt, kMu, kRollI, kRollJ, kConstants };
  static constexpr std::array<std::string_view, kConstants> constant_names = {
      "4/3 E* sqrt(R*)", "2 sqrt(5/6) (-beta) sqrt(2 E* sqrt(R*) m*)", "8 G* sqrt(R*)",
      "2 sqrt(5/6) (-beta) sqrt(8 G* sqrt(R*) m*)", "mu", "mu_r R_i", "mu_r R_j"};

  struct Effective {
    double r, m, e, g;  // R*, m*, E*, G*
  };
  static Effective effective(const ContactBody<Material>& a, const ContactBody<Material>& b, const Params& p) {
    const Material& mb = b.wall ? p.wall : b.material;
    auto compliance = [](const Material& m) { return (1 - m.poisson_ratio * m.poisson_ratio) / m.youngs_modulus; };
    auto shear = [](const Material& m) { return 2 * (2 - m.poisson_ratio) * (1 + m.poisson_ratio) / m.youngs_modulus; };
    return {b.wall ? a.radius : a.radius * b.radius / (a.radius + b.radius),
            b.wall ? a.mass : a.mass * b.mass / (a.mass + b.mass), 1.0 / (compliance(a.material) + compliance(mb)),
            1.0 / (shear(a.material) + shear(mb))};
  }
  static double beta(double e) {
    const double l = std::log(e);
    return l / std::sqrt(l * l + std::numbers::pi * std::numbers::pi);
  }

  static std::array<double, kConstants> constants(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                                  const Params& p) {
    const Effective x = effective(a, b, p);
    const double damp = 2.0 * std::sqrt(5.0 / 6.0) * (-beta(p.restitution));
    const double sr = std::sqrt(x.r);
    return {4.0 / 3.0 * x.e * sr,
            damp * std::sqrt(2.0 * x.e * sr * x.m),
            8.0 * x.g * sr,
            damp * std::sqrt(8.0 * x.g * sr * x.m),
            p.friction,
            p.rolling_friction * a.radius,
            b.wall ? 0.0 : p.rolling_friction * b.radius};
  }

  static double rayleigh_time(const ContactBody<Material>& s) {
    const double rho = s.mass / (4.0 / 3.0 * std::numbers::pi * s.radius * s.radius * s.radius);
    const double nu = s.material.poisson_ratio;
    const double g = s.material.youngs_modulus / (2.0 * (1.0 + nu));
    return std::numbers::pi * s.radius * std::sqrt(rho / g) / (0.1631 * nu + 0.8766);
  }
  static std::vector<StepTerm> critical_terms(const ContactBody<Material>& a, const ContactBody<Material>& b,
                                              const Params& p) {
    const Effective x = effective(a, b, p);
    const double v = p.impact_speed;
    std::vector<StepTerm> t{{rayleigh_time(a), "Rayleigh time"}};
    if (!b.wall) t.push_back({rayleigh_time(b), "Rayleigh time"});
    char at[48];
    std::snprintf(at, sizeof at, "Hertz contact time at %.3g m/s", v);
    t.push_back({2.87 * std::pow(x.m * x.m / (x.r * x.e * x.e * v), 0.2), at});
    return t;
  }

  // Grains of a size distribution (size_scaling.hpp): the stiffnesses go with sqrt(R*), the dampings
  // with sqrt(sqrt(R*) m*), the rolling torques with each grain's own radius.
  template <class T>
  [[gnu::always_inline]] static void resize(std::array<T, kConstants>& k, const SizeRatio<T>& q) {
    const T sr = sqrt_of(q.r);
    const T damp = sqrt_of(sr * q.m);
    k[kKh] = k[kKh] * sr;
    k[kSt] = k[kSt] * sr;
    k[kCn] = k[kCn] * damp;
    k[kCt] = k[kCt] * damp;
    k[kRollI] = k[kRollI] * q.ri;
    k[kRollJ] = k[kRollJ] * q.rj;
  }

  // History: the tangential spring d_t (m), seen from row i (odd when i and j trade places).
  static constexpr std::size_t kHistory = 3;
  static HistoryLayout history() { return {"hertz_mindlin.shear", {"shear.x", "shear.y", "shear.z"}}; }

  // `touching` masks lanes (or the scalar) in contact; elsewhere the spring resets and forces vanish.
  template <class T, class M>
  [[gnu::always_inline]] static ContactForce<T> evaluate(const M& touching, const ContactGeometry<T>& g,
                                  const std::array<T, kConstants>& k, const T& dt, std::array<T, kHistory>& h) {
    const T zero(0.0);
    const V3<T>& n = g.n;
    const T vn = dot(g.v, n);
    const V3<T> vt = g.v - vn * n;
    // sqrt(alpha) and alpha^(1/4), from an overlap kept >= 0 on lanes that do not touch.
    const T a = choose(g.delta > zero, g.delta, zero);
    const T sa = sqrt_of(a);
    const T qa = sqrt_of(sa);
    const T fn_signed = -(k[kKh] * a * sa) - k[kCn] * qa * vn;  // along n
    const T fn_mag = abs_of(fn_signed);

    const T st = k[kSt] * sa;
    V3<T> d = turn_spring(V3<T>{h[0], h[1], h[2]}, n);
    d = d + dt * vt;
    V3<T> ft = (-st) * d - (k[kCt] * qa) * vt;
    slide(ft, d, k[kMu] * fn_mag, st);

    // Constant directional torque against the relative spin (none where there is no spin).
    const T w2 = dot(g.w, g.w);
    const auto spins = w2 > T(1e-300);
    const T inv_w = choose(spins, rsqrt_of(choose(spins, w2, T(1.0))), zero);
    const V3<T> w_hat = inv_w * g.w;

    const V3<T> zv{zero, zero, zero};
    const V3<T> dk = choose(touching, d, zv);
    h = {dk.x, dk.y, dk.z};
    ContactForce<T> r;
    r.force_t = choose(touching, ft, zv);
    r.force = choose(touching, fn_signed * n + ft, zv);
    r.torque_i = choose(touching, (-(k[kRollI] * fn_mag)) * w_hat, zv);
    r.torque_j = choose(touching, (k[kRollJ] * fn_mag) * w_hat, zv);
    return r;
  }
};

}  // namespace gf
