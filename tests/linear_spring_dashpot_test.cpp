// The linear spring-dashpot-slider law of seed 000 on its own (systems/contact/linear_spring_dashpot.hpp):
// the Coulomb and rolling caps, the reset of the springs when a contact opens, the rotation of the tangential
// spring into the current tangent plane, and the SIMD twin (the same template on xsimd::batch<double>) lane by
// lane against the scalar law.
// GCC 12 reports a false -Wuninitialized inside its own avx512fintrin.h (_mm512_sqrt_pd passes
// _mm512_undefined_pd() as the unused merge source; GCC bug 105593) once xsimd::sqrt is inlined into the batch
// law. The diagnostic state is looked up at the header's line, so silencing it around the includes only leaves
// this test's own code fully checked.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
#include "systems/contact/linear_spring_dashpot.hpp"
#pragma GCC diagnostic pop

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

using gf::dot;
using gf::LinearSpringDashpot;
using gf::LsdCoeffs;
using gf::LsdResult;
using gf::LsdState;
using gf::V3;
using gf::test::ErrorKind;
using gf::test::norm;
using gf::test::record_analytic;
using V = V3<double>;

namespace {

V unit(const V& a) { return (1.0 / norm(a)) * a; }

// Seed 000 contact (Table 4) between two 3 mm glass spheres, damping from e = 0.3 on the effective masses.
LsdCoeffs<double> seed_coeffs() {
  LsdCoeffs<double> c{};
  c.kn = 1000.0;       // N/m
  c.kt = 600.0;        // N/m
  c.kr = 1e-5;         // N m/rad
  c.eta_n = 4.0e-3;    // N s/m   (order of 2 sqrt(m k) ln(1/e)/sqrt(pi^2 + ln^2 e) for m ~ 1.8e-5 kg)
  c.eta_t = 1.6e-3;    // N s/m
  c.eta_r = 6.0e-9;    // N m s/rad
  c.fs = 0.3;
  c.fr = 5e-5;  // m
  return c;
}

// A unit normal that is not aligned with any axis, so that every component of every vector is exercised.
const V kN = unit(V{0.3, -0.5, 0.8});
// A unit vector in the tangent plane of kN.
const V kT = unit(gf::cross(kN, V{1.0, 0.0, 0.0}));

}  // namespace

TEST_CASE("lsd: below the caps the forces are the linear spring-dashpot ones", "[contact][law]") {
  const LsdCoeffs<double> c = seed_coeffs();
  const double dt = 1e-5, delta = 2e-5;
  const V v = (-0.01) * kN + 1e-4 * kT;  // approaching, slow tangential motion: stays below the Coulomb cap
  const V w{0.1, -0.2, 0.05};
  LsdState<double> s{1e-7 * kT, {1e-6, 0.0, 0.0}};
  const V shear0 = s.shear;
  const V roll0 = s.roll;
  const LsdResult<double> r = LinearSpringDashpot::evaluate(true, kN, delta, v, w, c, dt, s);

  const double vn = dot(v, kN);
  const V vt = v - vn * kN;
  const V fn = (-c.kn * delta - c.eta_n * vn) * kN;
  const V d = shear0 + dt * vt;
  const V ft = (-c.kt) * d - c.eta_t * vt;
  const V a = roll0 + dt * w;
  const V tr = (-c.kr) * a - c.eta_r * w;
  // The law must be these expressions to round-off; 1e-13 relative leaves a few ulp for re-association.
  const double tol = 1e-13;
  REQUIRE(norm(r.force_t) < c.fs * norm(fn));  // the premise: below the Coulomb cap
  REQUIRE(norm(tr) < c.fr * norm(fn));         // and below the rolling cap
  CHECK(norm(r.force - (fn + ft)) <= tol * norm(fn));
  CHECK(norm(r.force_t - ft) <= tol * norm(ft));
  CHECK(norm(r.rolling_torque - tr) <= tol * norm(tr));
  CHECK(norm(s.shear - d) <= tol * norm(d));
  CHECK(norm(s.roll - a) <= tol * norm(a));
}

TEST_CASE("lsd: Coulomb cap, |F_t| = f_s |F_n| when sliding and the spring is shortened to the cap",
          "[contact][law]") {
  const LsdCoeffs<double> c = seed_coeffs();
  const double dt = 1e-5, delta = 1e-4;
  // Fast tangential sliding plus an old spring far beyond the cap.
  const V v = 0.02 * kN + 0.5 * kT + 0.1 * gf::cross(kN, kT);
  LsdState<double> s{1e-3 * unit(kT + 0.3 * gf::cross(kN, kT)), {0.0, 0.0, 0.0}};
  const V w{0.0, 0.0, 0.0};
  const LsdResult<double> r = LinearSpringDashpot::evaluate(true, kN, delta, v, w, c, dt, s);

  const double fn_signed = -c.kn * delta - c.eta_n * dot(v, kN);
  const double cap = c.fs * std::abs(fn_signed);
  const double ft = norm(r.force_t);
  const double spring = norm(s.shear);
  CAPTURE(ft, cap, spring, cap / c.kt);
  // Exact cap up to round-off in the few operations that scale the spring: 1e-13 relative.
  CHECK(std::abs(ft - cap) <= 1e-13 * cap);
  CHECK(std::abs(spring - cap / c.kt) <= 1e-13 * cap / c.kt);
  // Force along -d_t (the seed's Coulomb direction), in the tangent plane, normal part unchanged.
  CHECK(norm(r.force_t + c.kt * s.shear) <= 1e-13 * cap);
  CHECK(std::abs(dot(r.force_t, kN)) <= 1e-13 * cap);
  CHECK(norm(r.force - r.force_t - fn_signed * kN) <= 1e-13 * std::abs(fn_signed));
  // The uncapped force would have been far larger: the cap is what acted.
  CHECK(c.kt * 1e-3 > 10 * cap);

  // A step later, same normal force, tangential velocity reversed: the force starts from the cap and drops below
  // it at once because the spring was shortened (an ever-grown spring of 1e-3 m would keep it pinned at the cap).
  const V v2 = 0.02 * kN - 1e-3 * kT;
  const LsdResult<double> r2 = LinearSpringDashpot::evaluate(true, kN, delta, v2, w, c, dt, s);
  CAPTURE(norm(r2.force_t), cap);
  CHECK(norm(r2.force_t) < cap * (1.0 - 1e-6));
}

TEST_CASE("lsd: rolling cap, |T_r| = f_r |F_n| and the rolling spring is shortened to the cap",
          "[contact][law]") {
  const LsdCoeffs<double> c = seed_coeffs();
  const double dt = 1e-5, delta = 5e-5;
  const V v = -0.01 * kN;
  const V w = V{30.0, -10.0, 20.0};  // fast relative rolling
  LsdState<double> s{{0.0, 0.0, 0.0}, {2.0, 1.0, -3.0}};  // rolling spring far beyond the cap
  const LsdResult<double> r = LinearSpringDashpot::evaluate(true, kN, delta, v, w, c, dt, s);

  const double fn = std::abs(-c.kn * delta - c.eta_n * dot(v, kN));
  const double cap = c.fr * fn;
  const double tr = norm(r.rolling_torque);
  CAPTURE(tr, cap, norm(s.roll), cap / c.kr);
  CHECK(std::abs(tr - cap) <= 1e-13 * cap);
  CHECK(std::abs(norm(s.roll) - cap / c.kr) <= 1e-13 * cap / c.kr);
  CHECK(norm(r.rolling_torque + c.kr * s.roll) <= 1e-13 * cap);  // along -alpha
  CHECK(norm(c.kr * V{2.0, 1.0, -3.0}) > 10 * cap);              // the cap acted
  // No tangential motion, no tangential force (v - (v.n) n leaves ~1e-19 m/s of round-off).
  CHECK(norm(r.force_t) <= 1e-12 * c.fs * fn);
}

TEST_CASE("lsd: apart gives zero force and resets both springs", "[contact][law]") {
  const LsdCoeffs<double> c = seed_coeffs();
  LsdState<double> s{{1e-5, -2e-5, 3e-6}, {0.01, 0.02, -0.03}};
  const LsdResult<double> r =
      LinearSpringDashpot::evaluate(false, kN, -1e-6, V{0.1, 0.2, 0.3}, V{1.0, 2.0, 3.0}, c, 1e-5, s);
  CHECK(r.force.x == 0.0);
  CHECK(r.force.y == 0.0);
  CHECK(r.force.z == 0.0);
  CHECK(norm(r.force_t) == 0.0);
  CHECK(norm(r.rolling_torque) == 0.0);
  CHECK(norm(s.shear) == 0.0);
  CHECK(norm(s.roll) == 0.0);
}

TEST_CASE("lsd: the old spring is rotated into the current tangent plane keeping its length", "[contact][law]") {
  LsdCoeffs<double> c = seed_coeffs();
  c.eta_t = 0.0;
  c.fs = 1e6;  // no sliding: only the rotation acts
  const double delta = 1e-4;
  // A spring from an earlier contact frame: it has a component along the current normal.
  const V old = 1e-6 * unit(V{1.0, 2.0, -0.5});
  REQUIRE(std::abs(dot(unit(old), kN)) > 0.3);  // the premise: far from the tangent plane
  LsdState<double> s{old, {0.0, 0.0, 0.0}};
  // No relative motion, so the spring changes by rotation only.
  const LsdResult<double> r =
      LinearSpringDashpot::evaluate(true, kN, delta, V{0.0, 0.0, 0.0}, V{0.0, 0.0, 0.0}, c, 1e-5, s);
  CAPTURE(norm(s.shear), norm(old), dot(s.shear, kN));
  // Length kept and normal component removed, to round-off (1e-14 relative: a dozen operations).
  CHECK(std::abs(norm(s.shear) - norm(old)) <= 1e-14 * norm(old));
  CHECK(std::abs(dot(s.shear, kN)) <= 1e-14 * norm(old));
  // It points along the projection of the old spring (rotation, not an arbitrary direction).
  const V proj = old - dot(old, kN) * kN;
  CHECK(norm(unit(s.shear) - unit(proj)) <= 1e-14);
  CHECK(norm(r.force_t + c.kt * s.shear) <= 1e-14 * c.kt * norm(old));
}

// ---------------------------------------------------------------------------------------------------------------
// SIMD twin: the same template on xsimd::batch<double> (default architecture) must reproduce the scalar law.

namespace {

using B = xsimd::batch<double>;
using BB = xsimd::batch_bool<double>;
constexpr std::size_t kLanes = B::size;

struct Contact {
  bool touching;
  V n;
  double delta;
  V v, w;
  LsdCoeffs<double> c;
  LsdState<double> s;
};

// Random contacts in four families: apart, sticking, sliding (Coulomb cap), rolling cap; with edge cases
// (k_t = 0 or k_r = 0 lanes, a zero old spring and no tangential velocity) mixed in.
std::vector<Contact> random_contacts(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  auto rv = [&] { return V{u(rng), u(rng), u(rng)}; };
  std::vector<Contact> out;
  for (std::size_t i = 0; i < count; ++i) {
    Contact k{};
    const int family = static_cast<int>(i % 4);
    k.n = unit(rv());
    k.touching = family != 0;
    k.delta = k.touching ? 1e-5 * (0.1 + pos(rng)) : -1e-5 * pos(rng);
    k.c.kn = 500.0 + 1000.0 * pos(rng);
    k.c.kt = (i % 13 == 5) ? 0.0 : 300.0 + 600.0 * pos(rng);
    k.c.kr = (i % 11 == 7) ? 0.0 : 1e-5 * (0.5 + pos(rng));
    k.c.eta_n = 4e-3 * (0.5 + pos(rng));
    k.c.eta_t = 1.6e-3 * (0.5 + pos(rng));
    k.c.eta_r = k.c.kr > 0 ? 6e-9 * (0.5 + pos(rng)) : 0.0;
    k.c.fs = 0.1 + 0.5 * pos(rng);
    k.c.fr = 1e-5 + 1e-4 * pos(rng);
    const double vscale = family == 2 ? 1.0 : 1e-4;  // sliding family: fast tangential motion
    k.v = vscale * rv();
    k.w = (family == 3 ? 50.0 : 0.05) * rv();           // rolling-cap family: fast relative rolling
    k.s.shear = (family == 2 ? 1e-3 : 1e-8) * rv();
    k.s.roll = (family == 3 ? 0.5 : 1e-4) * rv();
    if (i % 17 == 9) {  // no old spring and no motion: the zero-length guards of the law
      k.s.shear = {0.0, 0.0, 0.0};
      k.v = {0.0, 0.0, 0.0};
    }
    out.push_back(k);
  }
  return out;
}

B lane_load(const std::vector<Contact>& cs, std::size_t b, double (*get)(const Contact&)) {
  alignas(64) std::array<double, kLanes> buf{};
  for (std::size_t l = 0; l < kLanes; ++l) buf[l] = get(cs[b + l]);
  return B::load_aligned(buf.data());
}

std::array<double, kLanes> lanes(const B& x) {
  alignas(64) std::array<double, kLanes> buf{};
  x.store_aligned(buf.data());
  return buf;
}

}  // namespace

TEST_CASE("lsd: the xsimd batch twin matches the scalar law lane by lane", "[contact][law][simd]") {
  const std::size_t count = 64 * kLanes;
  const std::vector<Contact> cs = random_contacts(count, 20240611);
  const double dt = 1e-5;

  // Scalar reference.
  std::vector<LsdResult<double>> ref(count);
  std::vector<LsdState<double>> ref_s(count);
  int apart = 0, stick = 0, slide = 0, roll_capped = 0;
  for (std::size_t i = 0; i < count; ++i) {
    const Contact& k = cs[i];
    LsdState<double> s = k.s;
    ref[i] = LinearSpringDashpot::evaluate(k.touching, k.n, k.delta, k.v, k.w, k.c, dt, s);
    ref_s[i] = s;
    if (!k.touching) {
      ++apart;
      continue;
    }
    const double fn = std::abs(-k.c.kn * k.delta - k.c.eta_n * dot(k.v, k.n));
    const double ft = norm(ref[i].force_t);
    if (std::abs(ft - k.c.fs * fn) <= 1e-12 * k.c.fs * fn)
      ++slide;
    else if (ft < k.c.fs * fn)
      ++stick;
    if (std::abs(norm(ref[i].rolling_torque) - k.c.fr * fn) <= 1e-12 * k.c.fr * fn) ++roll_capped;
  }
  INFO("contacts: " << apart << " apart, " << stick << " sticking, " << slide << " sliding, " << roll_capped
                    << " at the rolling cap; " << kLanes << " lanes");
  // The premise: every branch of the law is exercised, in many lanes.
  REQUIRE(apart >= 32);
  REQUIRE(stick >= 32);
  REQUIRE(slide >= 32);
  REQUIRE(roll_capped >= 32);

  // Batch evaluation; the worst lane of each output is checked once at the end.
  struct Worst {
    const char* what;
    double rel = 0.0;
    std::size_t lane = 0;
    int zero_mismatch = 0;  // lanes where the scalar result is exactly zero and the batch's is not
  };
  std::array<Worst, 5> worst{{{"force"}, {"force_t"}, {"rolling_torque"}, {"shear spring"}, {"rolling spring"}}};
  for (std::size_t b = 0; b < count; b += kLanes) {
    auto ld = [&](double (*get)(const Contact&)) { return lane_load(cs, b, get); };
    const V3<B> n{ld([](const Contact& k) { return k.n.x; }), ld([](const Contact& k) { return k.n.y; }),
                  ld([](const Contact& k) { return k.n.z; })};
    const V3<B> v{ld([](const Contact& k) { return k.v.x; }), ld([](const Contact& k) { return k.v.y; }),
                  ld([](const Contact& k) { return k.v.z; })};
    const V3<B> w{ld([](const Contact& k) { return k.w.x; }), ld([](const Contact& k) { return k.w.y; }),
                  ld([](const Contact& k) { return k.w.z; })};
    const B delta = ld([](const Contact& k) { return k.delta; });
    const BB touching = ld([](const Contact& k) { return k.touching ? 1.0 : 0.0; }) > B(0.5);
    const LsdCoeffs<B> c{ld([](const Contact& k) { return k.c.kn; }),    ld([](const Contact& k) { return k.c.kt; }),
                         ld([](const Contact& k) { return k.c.kr; }),    ld([](const Contact& k) { return k.c.eta_n; }),
                         ld([](const Contact& k) { return k.c.eta_t; }), ld([](const Contact& k) { return k.c.eta_r; }),
                         ld([](const Contact& k) { return k.c.fs; }),    ld([](const Contact& k) { return k.c.fr; })};
    LsdState<B> s{{ld([](const Contact& k) { return k.s.shear.x; }), ld([](const Contact& k) { return k.s.shear.y; }),
                   ld([](const Contact& k) { return k.s.shear.z; })},
                  {ld([](const Contact& k) { return k.s.roll.x; }), ld([](const Contact& k) { return k.s.roll.y; }),
                   ld([](const Contact& k) { return k.s.roll.z; })}};
    const LsdResult<B> r = LinearSpringDashpot::evaluate(touching, n, delta, v, w, c, B(dt), s);

    // Each output vector lane by lane, relative to the size of the scalar vector.
    auto compare = [&](const V3<B>& got, auto scalar_of, Worst& wst) {
      const auto gx = lanes(got.x), gy = lanes(got.y), gz = lanes(got.z);
      for (std::size_t l = 0; l < kLanes; ++l) {
        const V want = scalar_of(b + l);
        const double err = norm(V{gx[l], gy[l], gz[l]} - want);
        const double scale = norm(want);
        if (scale == 0.0) {
          if (err != 0.0) ++wst.zero_mismatch;
          continue;
        }
        if (err / scale > wst.rel) {
          wst.rel = err / scale;
          wst.lane = b + l;
        }
      }
    };
    compare(r.force, [&](std::size_t i) { return ref[i].force; }, worst[0]);
    compare(r.force_t, [&](std::size_t i) { return ref[i].force_t; }, worst[1]);
    compare(r.rolling_torque, [&](std::size_t i) { return ref[i].rolling_torque; }, worst[2]);
    compare(s.shear, [&](std::size_t i) { return ref_s[i].shear; }, worst[3]);
    compare(s.roll, [&](std::size_t i) { return ref_s[i].roll; }, worst[4]);
  }
  double worst_all = 0.0;
  for (const Worst& wst : worst) {
    INFO(wst.what << ": worst relative difference " << wst.rel << " in contact " << wst.lane);
    // 1e-12 relative: the batch runs the same operations in the same order, but not with the same
    // roundings. Its reciprocal square roots (rsqrt_of in vec3.hpp: turning the spring, the slider
    // caps) are, on AVX-512, the 14-bit hardware estimate refined by two Newton steps, within a few ulp
    // of the scalar path's correctly rounded 1 / sqrt (without AVX-512 a correctly rounded sqrt and a
    // division, as in the scalar path); its square roots are correctly rounded in both paths; and the
    // compiler may fuse a*b+c into an FMA in one path and not in the other (-march=native). A few ulp
    // (1.1e-16 each) over a few dozen operations, amplified by the cancellation in v - (v.n) n by at
    // most ~1e2 for these random contacts: ~1e-13 at worst. 1e-12 keeps that margin yet catches any
    // real divergence (a wrong selection or lane mix-up is an O(1) error).
    record_analytic({.case_name = "xsimd law vs scalar law, " + std::to_string(count) + " random contacts, " +
                                  std::to_string(kLanes) + " lanes",
                     .quantity = std::string(wst.what) + ": largest difference / its size", .closed_form = "identical",
                     .error = wst.rel, .kind = ErrorKind::relative, .tolerance = 1e-12});
    CHECK(wst.rel <= 1e-12);
    // Apart lanes (and zero springs) must be exact zeros in the batch too: they come from selections, not sums.
    CHECK(wst.zero_mismatch == 0);
    worst_all = std::max(worst_all, wst.rel);
  }
  WARN("SIMD twin: " << count << " contacts, " << kLanes << " lanes; worst relative difference to scalar " << worst_all
                     << " (tolerance 1e-12)");
}
