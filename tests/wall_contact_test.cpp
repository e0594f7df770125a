// Sphere-wall contacts through the whole engine: restitution and contact time against a plane (with the sphere's
// own mass), the resting overlap m g / k_n on a plane and on the inner wall of a cylinder, sticking and sliding on
// an incline, rolling resistance, and the drag of a rotating drum wall.
//
// What the seed's model predicts on an incline (theta the tilt, N = m g cos(theta), L = r - delta/2 the lever arm):
//  - sliding needs the friction force to exceed f_s N: tan(theta) > f_s;
//  - but a sphere need not slide to move: it can roll. Holding it still needs, besides F_t = m g sin(theta), a
//    torque L F_t about its centre from the rolling resistance, which is capped at f_r N. So the sphere stays put
//    only if tan(theta) < f_s AND tan(theta) < f_r / L. With the seed's values (f_r = 5e-5 m, r = 1.5 mm) the
//    second bound is 0.033 << f_s = 0.3: on any slope steeper than 1.9 degrees a seed sphere ROLLS, long before it
//    could slide, accelerating at a = g (sin(theta) - (f_r/L) cos(theta)) / (1 + I/(m L^2)) without slip.
//  - the textbook Coulomb threshold tan(theta) = f_s is therefore tested with a rolling resistance large enough to
//    forbid rolling (f_r = 2 r): below it the sphere stays (elastic creep only), above it it slides as a block at
//    a = g (sin(theta) - f_s cos(theta)).
//  - without rolling resistance a sphere rolls without slip while tan(theta) < 3.5 f_s and slides (spinning up)
//    above; the centre then accelerates at g (sin(theta) - f_s cos(theta)) and the spin at f_s N L / I.
// Slopes are reached by tilting gravity slowly (a quasi-static ramp), as one tilts a plank: a sudden tilt would
// load the springs dynamically and overshoot the static friction force.
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <vector>

#include "systems/contact/laws.hpp"
#include "systems/walls/wall_contact.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Grains;
using gf::test::contact_time;
using gf::test::ErrorKind;
using gf::test::record_analytic;
using gf::test::set_override;
using V = gf::V3<double>;

namespace {

const std::string kPlane = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/tests/sphere_on_plane.toml";
const std::string kDrum = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/tests/sphere_in_drum.toml";

// The scenes' values, restated so that the references are computed independently of the engine.
constexpr double kD = 3e-3, kR = 1.5e-3, kRho = 2500.0;
constexpr double kKn = 1000.0, kKt = 600.0, kKr = 1e-5, kG = 9.81;
constexpr double kDrumR = 0.075, kDrumOmega = 0.5;
const double kM = kRho * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
const double kI = 0.4 * kM * kR * kR;

// The scenes hold one grain: row 0.
V pos(const Grains& g) { return {g.pos.x[0], g.pos.y[0], g.pos.z[0]}; }
V vel(const Grains& g) { return {g.vel.x[0], g.vel.y[0], g.vel.z[0]}; }
V spin(const Grains& g) { return {g.omega.x[0], g.omega.y[0], g.omega.z[0]}; }
void place(Grains& g, const V& x, const V& v, const V& w) {
  g.pos.x[0] = x.x, g.pos.y[0] = x.y, g.pos.z[0] = x.z;
  g.vel.x[0] = v.x, g.vel.y[0] = v.y, g.vel.z[0] = v.z;
  if (g.spin) g.omega.x[0] = w.x, g.omega.y[0] = w.y, g.omega.z[0] = w.z;
}

// Least-squares slope of y(t).
double slope(const std::vector<double>& t, const std::vector<double>& y) {
  const double n = static_cast<double>(t.size());
  double st = 0, sy = 0;
  for (std::size_t i = 0; i < t.size(); ++i) st += t[i], sy += y[i];
  const double tm = st / n, ym = sy / n;
  double num = 0, den = 0;
  for (std::size_t i = 0; i < t.size(); ++i) num += (t[i] - tm) * (y[i] - ym), den += (t[i] - tm) * (t[i] - tm);
  return num / den;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

TEST_CASE("wall: sphere-plane restitution and contact time use the sphere's own mass", "[contact][wall]") {
  for (const double e : {0.3, 0.7}) {
    const double tc = contact_time(kM, kKn, e);  // particle-wall: m = m_i
    // dt = t_c/1000: as for pairs (tests/pair_contact_test.cpp), the step count quantises the duration to 0.1 %,
    // and the jump of the dashpot force at touch-down and lift-off gives a restitution error of at most
    // ~2 ln(1/e)/1000, 0.21 % at e = 0.3 and 0.05 % at e = 0.7, inside the 0.5 % tolerance.
    const double dt = tc / 1000.0;
    DemSimulation sim = DemSimulation::from_file(
        kPlane, {set_override("contact.en", e), set_override("run.dt", dt), "run.gravity=[0,0,0]"});
    Grains& g = sim.grains();
    const double v0 = 0.2;
    place(g, {0, kR + 1e-4, 0}, {0, -v0, 0}, {0, 0, 0});
    std::int64_t in_contact = 0;
    bool touched = false;
    int after = 0;
    for (int k = 0; k < 10000 && after < 10; ++k) {
      sim.advance(1);
      if (kR - pos(g).y > 0.0) {
        touched = true;
        ++in_contact;
      } else if (touched) {
        ++after;
      }
    }
    REQUIRE(after >= 10);
    const double e_meas = vel(g).y / v0;
    const double de = e_meas / e - 1.0;
    const double dtc = static_cast<double>(in_contact) * dt / tc - 1.0;
    INFO("e = " << e << ": measured restitution " << e_meas << ", contact " << in_contact * dt * 1e3 << " ms vs "
                << tc * 1e3 << " ms");
    WARN("sphere-plane, e = " << e << ": restitution error " << de * 100 << " %, contact time error " << dtc * 100
                              << " %");
    // Tolerances of the task; the effective mass of a pair (m/2 for equal spheres) instead of m_i would be off by
    // 29 % in t_c.
    const double tol_e = 0.005, tol_tc = 0.01;
    const std::string case_name = "sphere–plane, e = " + gf::test::csv_number(e, 3);
    record_analytic({.case_name = case_name, .quantity = "restitution", .closed_form = "e", .reference = e,
                     .measured = e_meas, .error = 100 * de, .kind = ErrorKind::percent, .tolerance = 100 * tol_e});
    record_analytic({.case_name = case_name, .quantity = "contact time (s)",
                     .closed_form = "√(m/k_n)·√(π² + ln²e), m = m_i", .reference = tc,
                     .measured = static_cast<double>(in_contact) * dt, .error = 100 * dtc, .kind = ErrorKind::percent,
                     .tolerance = 100 * tol_tc});
    CHECK(std::abs(de) < tol_e);
    CHECK(std::abs(dtc) < tol_tc);
    // A head-on bounce stays head-on: no tangential force, no spin.
    CHECK(std::abs(vel(g).x) + std::abs(vel(g).z) == 0.0);
  }
}

// Resting overlap: the sphere falls 0.2 mm, bounces (en = 0.3) and settles; static equilibrium k_n delta = m g is
// an exact fixed point of velocity Verlet (v = 0 and zero net force), so the settled overlap is m g / k_n up to the
// residual of the decaying oscillation, exp(-zeta omega_0 t) ~ e^-150 after 0.1 s, and round-off: r - y loses ~4
// digits of y's 16 (delta/r = 2e-4), so ~1e-12 relative. The task asks for 1 %; we assert 1e-6, still 1e6 times the
// expected error, so that a small systematic bias (a gravity kick missing a step, a wrong lever in the normal
// direction) would show too.
TEST_CASE("wall: resting overlap on a plane is m g / k_n", "[contact][wall]") {
  DemSimulation sim = DemSimulation::from_file(kPlane);
  sim.advance(sim.scene().main_steps());
  const Grains& g = sim.grains();
  const double delta = kR - pos(g).y;
  const double ref = kM * kG / kKn;
  const double err = delta / ref - 1.0;
  WARN("resting overlap on a plane: " << delta << " m vs m g/k_n = " << ref << " m, relative error " << err);
  record_analytic({.case_name = "sphere resting on a plane", .quantity = "overlap (m)", .closed_form = "m g / k_n",
                   .reference = ref, .measured = delta, .error = err, .kind = ErrorKind::relative, .tolerance = 1e-6});
  CHECK(std::abs(err) < 1e-6);
  CHECK(std::abs(vel(g).y) < 1e-9);  // at rest: the settling is complete
}

TEST_CASE("wall: resting overlap on the inner wall of a cylinder is m g / k_n", "[contact][wall]") {
  DemSimulation sim = DemSimulation::from_file(kDrum, {"wall.0.omega=0"});
  sim.advance(sim.scene().main_steps());
  const Grains& g = sim.grains();
  const V p = pos(g);
  const double delta = kR - (kDrumR - std::sqrt(p.x * p.x + p.y * p.y));
  const double ref = kM * kG / kKn;
  const double err = delta / ref - 1.0;
  WARN("resting overlap on a cylinder wall: " << delta << " m vs m g/k_n = " << ref << " m, relative error " << err);
  // Same reasoning as on the plane; r - (R - rho) cancels more digits (R = 75 mm): ~1e-10 relative.
  record_analytic({.case_name = "sphere resting on a drum's inner wall (still)", .quantity = "overlap (m)",
                   .closed_form = "m g / k_n", .reference = ref, .measured = delta, .error = err,
                   .kind = ErrorKind::relative, .tolerance = 1e-6});
  CHECK(std::abs(err) < 1e-6);
  CHECK(std::abs(p.x) < 1e-12);  // at the bottom, not dragged anywhere
  CHECK(std::abs(p.z) == 0.0);   // no end-wall contact
}

// ---------------------------------------------------------------------------------------------------------------
// Incline: the plane y = 0 stays, gravity is tilted by theta about z, so "down the slope" is +x.

namespace {

struct InclineRun {
  std::vector<double> t, x, vx, wz, slip;  // after the ramp
  double lever = 0;                        // L = r - delta/2 at the final normal load
  double max_abs_slip_ratio = 0;           // max |slip| / max(|v_x|, 1e-12) after the ramp
};

// Tilts gravity from 0 to theta over `ramp` seconds (smooth cosine ramp), then holds it for `hold` seconds.
InclineRun incline(double tan_theta, double fs, double fr, double ramp, double hold) {
  const double theta = std::atan(tan_theta);
  DemSimulation sim = DemSimulation::from_file(
      kPlane, {set_override("contact.friction", fs), set_override("contact.rolling_friction", fr)});
  Grains& g = sim.grains();
  auto& grav = sim.world().resources.get<gf::Gravity>();
  const double dt = sim.scene().dt;
  place(g, {0, kR - kM * kG / kKn, 0}, {0, 0, 0}, {0, 0, 0});  // resting on the level plane
  InclineRun out;
  out.lever = kR - 0.5 * kM * kG * std::cos(theta) / kKn;
  const auto ramp_steps = static_cast<std::int64_t>(std::llround(ramp / dt));
  const auto total = ramp_steps + static_cast<std::int64_t>(std::llround(hold / dt));
  for (std::int64_t k = 0; k < total; ++k) {
    const double s = std::min(1.0, static_cast<double>(k) / static_cast<double>(ramp_steps));
    const double th = theta * 0.5 * (1.0 - std::cos(std::numbers::pi * s));
    grav.x = kG * std::sin(th);
    grav.y = -kG * std::cos(th);
    sim.advance(1);
    if (k >= ramp_steps) {
      const double slip = vel(g).x + out.lever * spin(g).z;  // contact-point velocity along the slope
      out.t.push_back(sim.world().clock.t);
      out.x.push_back(pos(g).x);
      out.vx.push_back(vel(g).x);
      out.wz.push_back(spin(g).z);
      out.slip.push_back(slip);
    }
  }
  return out;
}

// The tail of a run, from time t0 on.
InclineRun tail(const InclineRun& r, double t0) {
  InclineRun o;
  o.lever = r.lever;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    if (r.t[i] < t0) continue;
    o.t.push_back(r.t[i]), o.x.push_back(r.x[i]), o.vx.push_back(r.vx[i]), o.wz.push_back(r.wz[i]);
    o.slip.push_back(r.slip[i]);
    o.max_abs_slip_ratio = std::max(o.max_abs_slip_ratio, std::abs(r.slip[i]) / std::max(std::abs(r.vx[i]), 1e-12));
  }
  return o;
}

// Elastic creep of a stuck sphere: F_t = m g sin(theta) stretches the tangential spring by F_t/k_t and the torque
// L F_t turns the rolling spring by L F_t/k_r, which rolls the centre by a further L^2 F_t/k_r.
const char* const kCreep = "elastic creep m g sin θ (1/k_t + L²/k_r)";
double creep(double tan_theta, double lever) {
  const double s = std::sin(std::atan(tan_theta));
  return kM * kG * s * (1.0 / kKt + lever * lever / kKr);
}

}  // namespace

TEST_CASE("wall: incline, Coulomb threshold with rolling forbidden (f_r = 2 r)", "[contact][wall][incline]") {
  const double fs = 0.3, fr = 2.0 * kR;
  SECTION("tan(theta) = 0.9 f_s: the sphere sticks; only the springs stretch") {
    const double tt = 0.9 * fs;
    const InclineRun r = tail(incline(tt, fs, fr, 0.1, 0.3), 0.35);
    const double x_end = r.x.back(), ref = creep(tt, r.lever);
    const double err = x_end / ref - 1.0;
    WARN("incline stick, tan = 0.9 f_s: displacement " << x_end << " m vs elastic creep " << ref << " m (error "
                                                        << err * 100 << " %), final |v| " << std::abs(r.vx.back()));
    // 1 %: the creep is a static equilibrium (exact) once the ramp's rolling-spring oscillation (period ~21 ms,
    // modal damping ratio ~0.2) has decayed for 0.25 s, ~1e-6 of its amplitude. A slip of the contact would add a
    // permanent displacement; sliding would grow it without bound.
    record_analytic({.case_name = "incline, tan θ = 0.9 f_s, rolling blocked (f_r = 2 r): sticks",
                     .quantity = "displacement (m)", .closed_form = kCreep, .reference = ref, .measured = x_end,
                     .error = 100 * err, .kind = ErrorKind::percent, .tolerance = 1});
    CHECK(std::abs(err) < 0.01);
    CHECK(std::abs(r.vx.back()) < 1e-6);  // at rest (sliding at 1.1 f_s reaches 0.03 m/s within 0.1 s)
  }
  SECTION("tan(theta) = 1.1 f_s: the sphere slides as a block at g (sin - f_s cos)") {
    const double tt = 1.1 * fs;
    const InclineRun r = tail(incline(tt, fs, fr, 0.1, 0.3), 0.15);
    const double th = std::atan(tt);
    const double a = slope(r.t, r.vx), ref = kG * (std::sin(th) - fs * std::cos(th));
    const double wdot = slope(r.t, r.wz);
    const double err = a / ref - 1.0;
    WARN("incline slide, tan = 1.1 f_s: a = " << a << " m/s^2 vs g(sin - f_s cos) = " << ref << " (error "
                                               << err * 100 << " %), spin rate " << wdot << " rad/s^2");
    // 1 %: at steady sliding the tangential force is exactly f_s N and the rolling spring holds the spin at zero;
    // the fit over 0.15 s averages the small remaining spring oscillation. A cap on the wrong normal force or a
    // missing cap would be off by >= 10 % (the margin over the threshold is 10 %, so a is 1/10 of g sin).
    record_analytic({.case_name = "incline, tan θ = 1.1 f_s, rolling blocked (f_r = 2 r): slides",
                     .quantity = "acceleration (m/s²)", .closed_form = "g (sin θ − f_s cos θ)", .reference = ref,
                     .measured = a, .error = 100 * err, .kind = ErrorKind::percent, .tolerance = 1});
    CHECK(std::abs(err) < 0.01);
    CHECK(std::abs(wdot) < 1e-3 * a / kR);  // no rolling
  }
}

TEST_CASE("wall: incline with the seed's rolling resistance: it rolls unless tan(theta) < f_r/L",
          "[contact][wall][incline]") {
  const double fs = 0.3, fr = 5e-5;  // seed 000, Table 4
  SECTION("tan(theta) = 0.6 f_r/r: rolling resistance holds the sphere") {
    const double tt = 0.6 * fr / kR;
    const InclineRun r = tail(incline(tt, fs, fr, 0.1, 0.4), 0.45);
    const double x_end = r.x.back(), ref = creep(tt, r.lever);
    const double err = x_end / ref - 1.0;
    WARN("incline, seed f_r, tan = 0.6 f_r/r: displacement " << x_end << " m vs elastic creep " << ref
                                                              << " m (error " << err * 100 << " %)");
    record_analytic({.case_name = "incline, seed f_r, tan θ = 0.6 f_r/r: held", .quantity = "displacement (m)",
                     .closed_form = kCreep, .reference = ref, .measured = x_end, .error = 100 * err,
                     .kind = ErrorKind::percent, .tolerance = 1});
    CHECK(std::abs(err) < 0.01);  // as for the Coulomb stick case
    CHECK(std::abs(r.vx.back()) < 1e-6);
  }
  SECTION("tan(theta) = 3 f_r/r (< f_s): the sphere rolls without slipping") {
    const double tt = 3.0 * fr / kR;
    const InclineRun r = tail(incline(tt, fs, fr, 0.1, 0.3), 0.15);
    const double th = std::atan(tt), L = r.lever;
    const double ref = kG * (std::sin(th) - fr / L * std::cos(th)) / (1.0 + kI / (kM * L * L));
    const double a = slope(r.t, r.vx);
    const double err = a / ref - 1.0;
    WARN("incline roll, seed f_r, tan = 3 f_r/r: a = " << a << " m/s^2 vs 5/7 g (sin - f_r/L cos) = " << ref
                                                        << " (error " << err * 100 << " %), max |slip|/v "
                                                        << r.max_abs_slip_ratio);
    // 1 %: steady rolling with the rolling torque at its cap f_r N is again an exact balance once the spring
    // transients have decayed; the 5/7 factor alone (a sphere sliding or not rolling) would be off by 29 %, and
    // ignoring the rolling resistance by 50 %.
    record_analytic({.case_name = "incline, seed f_r, tan θ = 3 f_r/r: rolls", .quantity = "acceleration (m/s²)",
                     .closed_form = "g (sin θ − (f_r/L) cos θ) / (1 + I/(m L²)) ≈ 5/7 g (sin θ − (f_r/L) cos θ)",
                     .reference = ref, .measured = a, .error = 100 * err, .kind = ErrorKind::percent, .tolerance = 1});
    CHECK(std::abs(err) < 0.01);
    // Rolling, not sliding: the contact point is at rest to 1e-3 of the speed (the tangential spring is static).
    CHECK(r.max_abs_slip_ratio < 1e-3);
    CHECK(slope(r.t, r.wz) < 0.0);  // rolls forward: spin about -z for motion along +x
  }
}

TEST_CASE("wall: incline without rolling resistance slides and spins up above tan(theta) = 3.5 f_s",
          "[contact][wall][incline]") {
  const double fs = 0.1, tt = 0.5;  // 0.5 > 3.5 f_s = 0.35
  const InclineRun r = tail(incline(tt, fs, 0.0, 0.1, 0.2), 0.12);
  const double th = std::atan(tt);
  const double a = slope(r.t, r.vx), ref = kG * (std::sin(th) - fs * std::cos(th));
  const double wdot = slope(r.t, r.wz);
  const double wref = -fs * kM * kG * std::cos(th) * r.lever / kI;  // friction up the slope spins it forward
  WARN("incline slide with spin, f_s = 0.1, tan = 0.5: a = " << a << " vs " << ref << " (error "
                                                              << (a / ref - 1) * 100 << " %), spin-up " << wdot
                                                              << " vs " << wref << " (error " << (wdot / wref - 1) * 100
                                                              << " %)");
  // 1 %: constant kinetic friction f_s N on a sliding contact gives exactly these accelerations; a wrong sign of the
  // wall torque would reverse the spin-up, a wrong lever arm change its size by the lever's error.
  CHECK(std::abs(a / ref - 1.0) < 0.01);
  CHECK(std::abs(wdot / wref - 1.0) < 0.01);
}

TEST_CASE("wall: a sphere whose species does not rotate slides to rest at f_s g, and has no spin columns",
          "[contact][wall][rotation]") {
  // Launched at v0 = 0.2 m/s along the level plane without spin. Without rotation the contact slides
  // until it stops: v = v0 - f_s g t, distance v0^2 / (2 f_s g). With rotation the same friction spins
  // it up and it rolls from t = 2 v0 / (7 f_s g) = 19 ms at 5/7 v0: at 50 ms the two differ by far.
  const double v0 = 0.2, fs = 0.3;
  auto launch = [&](bool rotates) {
    DemSimulation sim = DemSimulation::from_file(kPlane, {std::string("species.0.rotates=") + (rotates ? "true" : "false")});
    place(sim.grains(), {0, kR - kM * kG / kKn, 0}, {v0, 0, 0}, {0, 0, 0});  // resting on the plane
    return sim;
  };
  DemSimulation slides = launch(false);
  Grains& g = slides.grains();
  CHECK_FALSE(g.spin);
  CHECK(g.omega.x.size() == 0);  // no spin columns at all
  CHECK(g.torque.x.size() == 0);
  CHECK(g.wall_torque.x.size() == 0);
  std::vector<double> t, v;
  while (slides.world().clock.t < 0.05) {
    slides.advance(1);
    if (slides.world().clock.t > 0.005) t.push_back(slides.world().clock.t), v.push_back(vel(g).x);
  }
  const double a = slope(t, v);
  // 1 %: kinetic friction f_s N with N = m g is the only horizontal force while it slides.
  CHECK(a == Approx(-fs * kG).epsilon(0.01));
  const double v_slid = vel(g).x;
  slides.advance(5000);  // 50 ms more: long stopped (stop at 68 ms)
  CHECK(std::abs(vel(g).x) < 1e-4 * v0);
  // 1 %: the distance of uniform deceleration; the stick at the end creeps by about f_s m g / k_t = 0.2 um.
  CHECK(pos(g).x == Approx(v0 * v0 / (2.0 * fs * kG)).epsilon(0.01));

  DemSimulation rolls = launch(true);
  CHECK(rolls.grains().omega.x.size() == 1);
  rolls.advance(5000);
  CHECK(v_slid < 0.3 * v0);            // v0 - f_s g t = 0.26 v0
  CHECK(vel(rolls.grains()).x > 0.6 * v0);  // rolling at about 5/7 v0, slowed only by rolling friction

  // A checkpoint without spin columns resumes only into a scene whose species do not rotate either.
  gf::test::TempDir dir("no_rotation");
  gf::CheckpointWriter out;
  gf::save_dem_state(out, slides.world(), slides.scene());
  out.write(dir.path / "slides.gfc");
  const gf::CheckpointReader in(dir.path / "slides.gfc");
  DemSimulation again = launch(false);
  again.resume(in);
  CHECK(pos(again.grains()).x == pos(g).x);
  DemSimulation spinning = launch(true);
  CHECK_THROWS_WITH(spinning.resume(in), Catch::Contains("do not rotate") && Catch::Contains("Fix:"));
}

TEST_CASE("wall: rolling friction decelerates a rolling sphere at 5 f_r g / (7 r)", "[contact][wall]") {
  // Seed rolling friction f_r = 5e-5 m. Rolling without slip, the capped rolling torque f_r m g about the centre
  // is the only horizontal drive: (m + I/L^2) a = -f_r m g / L, i.e. a = -5 f_r g / (7 r) for L = r.
  DemSimulation sim = DemSimulation::from_file(kPlane);
  Grains& g = sim.grains();
  const double delta0 = kM * kG / kKn, L = kR - 0.5 * delta0, v0 = 0.1;
  place(g, {0, kR - delta0, 0}, {v0, 0, 0}, {0, 0, -v0 / L});  // rolling along +x without slip
  std::vector<double> t, vx;
  double max_slip = 0;
  for (int k = 0; k < 20000; ++k) {  // 0.2 s: v drops from 0.1 to 0.053 m/s
    sim.advance(1);
    if (sim.world().clock.t < 0.02) continue;  // let the tangential spring settle (period ~0.1 ms)
    t.push_back(sim.world().clock.t);
    vx.push_back(vel(g).x);
    max_slip = std::max(max_slip, std::abs(vel(g).x + L * spin(g).z));
  }
  const double a = slope(t, vx);
  const double ref = -(5e-5 * kM * kG / L) / (kM + kI / (L * L));
  const double err = a / ref - 1.0;
  WARN("rolling friction: a = " << a << " m/s^2 vs -5 f_r g/(7 r) = " << -5.0 * 5e-5 * kG / (7 * kR)
                                << " (with L: " << ref << "), error " << err * 100 << " %, max slip " << max_slip
                                << " m/s");
  // 2 % (the task's); expected far smaller: a steady capped torque on a rolling sphere is an exact balance. Without
  // the I/L^2 term (a sliding block) the rate would be 40 % higher.
  record_analytic({.case_name = "sphere rolling on a plane, slowed by the rolling-friction cap",
                   .quantity = "acceleration (m/s²)",
                   .closed_form = "−(f_r g/L) / (1 + I/(m L²)) ≈ −5 f_r g/(7 r)", .reference = ref, .measured = a,
                   .error = 100 * err, .kind = ErrorKind::percent, .tolerance = 2});
  CHECK(std::abs(err) < 0.02);
  CHECK(max_slip < 1e-4 * v0);  // it rolls: the contact point stays at rest
}

TEST_CASE("wall: rolling resistance acts on the spin relative to a turning wall (turntable)", "[contact][wall]") {
  // The plane turns about its own normal (a turntable, omega = 20 rad/s about +y through the origin); the sphere
  // rests on the axis, where the table's surface does not move, so only the relative spin w_i - w_wall matters.
  // The law's rolling torque acts on the whole relative angular velocity (twist included) and is capped at f_r N:
  // the resting sphere is spun up about +y at f_r m g / I = 5 f_r g / (2 r^2) = 545 rad/s^2 until it turns with the
  // table (37 ms), then stays there (relative spin zero, rolling spring static).
  const double w_table = 20.0, fr = 5e-5;
  DemSimulation sim = DemSimulation::from_file(kPlane, {set_override("wall.0.omega", w_table)});
  Grains& g = sim.grains();
  place(g, {0, kR - kM * kG / kKn, 0}, {0, 0, 0}, {0, 0, 0});
  const double rate_ref = fr * kM * kG / kI;
  std::vector<double> t, wy;
  for (int k = 0; k < 10000; ++k) {  // 100 ms
    sim.advance(1);
    const double tk = sim.world().clock.t;
    if (tk > 0.002 && tk < 0.03) t.push_back(tk), wy.push_back(spin(g).y);
  }
  const double rate = slope(t, wy);
  WARN("turntable: spin-up " << rate << " rad/s^2 vs f_r m g / I = " << rate_ref << " (error "
                             << (rate / rate_ref - 1) * 100 << " %), final spin " << spin(g).y << " rad/s vs table "
                             << w_table);
  // 1 %: a capped torque f_r N with N = m g exactly at rest; the sign says the torque drives the sphere towards
  // the table's spin (relative spin), not against its own spin.
  CHECK(std::abs(rate / rate_ref - 1.0) < 0.01);
  // 1e-4: on reaching the table's spin the rolling spring is still at the cap and overshoots; the oscillation
  // (period 2 pi sqrt(I/k_r) = 11 ms, amplitude ~1 rad/s, decay time 1/(zeta omega) = 5 ms at e_r = 0.3) has
  // decayed by e^-12 in the remaining 63 ms.
  CHECK(std::abs(spin(g).y / w_table - 1.0) < 1e-4);
  CHECK(std::abs(pos(g).x) + std::abs(pos(g).z) < 1e-12);  // on the axis, not thrown off
}

TEST_CASE("wall: a rotating drum wall drags a resting sphere along its motion", "[contact][wall][drum]") {
  // The drum (omega = +0.5 rad/s about +z) moves at +x at its bottom, U = omega R = 0.0375 m/s. The sphere rests
  // there at first: the contact slides, so the sphere accelerates along +x at f_s g and spins up about +z at
  // f_s m g L / I until its contact point moves with the wall. Friction acts at the contact point, so the angular
  // momentum about it, m v L + I w, is conserved: rolling starts at v = U / (1 + m L^2 / I) = 2U/7.
  // Rolling resistance is switched off here: it would act on the spin relative to the drum and change sign when the
  // sphere's spin passes the drum's, which spoils the clean bowling-ball result.
  DemSimulation sim = DemSimulation::from_file(kDrum, {"contact.rolling_friction=0"});
  Grains& g = sim.grains();
  const double fs = 0.3;
  const double delta0 = kM * kG / kKn, L = kR - 0.5 * delta0;
  place(g, {0, -(kDrumR - kR + delta0), 0}, {0, 0, 0}, {0, 0, 0});  // at rest, at the resting overlap
  const double U = kDrumOmega * (kDrumR - 0.5 * delta0);           // wall speed at the contact point
  const double t_roll = U / (fs * kG * (1.0 + kM * L * L / kI));   // 3.6 ms
  std::vector<double> t, vx, wz;
  for (int k = 0; k < 800; ++k) {  // 8 ms
    sim.advance(1);
    const double tk = sim.world().clock.t;
    if (tk > 0.1 * t_roll && tk < 0.8 * t_roll) {
      t.push_back(tk);
      vx.push_back(vel(g).x);
      wz.push_back(spin(g).z);
    }
  }
  const double a = slope(t, vx), wdot = slope(t, wz);
  const double a_ref = fs * kG, w_ref = fs * kM * kG * L / kI;
  const double v_end = vel(g).x, v_ref = U / (1.0 + kM * L * L / kI);
  WARN("drum drag: a = " << a << " vs f_s g = " << a_ref << " (error " << (a / a_ref - 1) * 100 << " %), spin-up "
                         << wdot << " vs " << w_ref << " (error " << (wdot / w_ref - 1) * 100 << " %), rolling speed "
                         << v_end << " vs 2U/7 = " << v_ref << " (error " << (v_end / v_ref - 1) * 100 << " %)");
  // Direction first: the sphere goes the way the wall moves and spins the way the drum turns.
  REQUIRE(a > 0.0);
  REQUIRE(wdot > 0.0);
  // 1 % on the sliding phase: kinetic friction f_s m g exactly, the curvature of the drum adds a gravity component
  // of order g phi with phi < 3e-4 rad over 3 ms (0.1 %).
  const std::string drag = "turning drum wall drags a resting sphere";
  record_analytic({.case_name = drag, .quantity = "acceleration while sliding (m/s²)", .closed_form = "f_s g",
                   .reference = a_ref, .measured = a, .error = 100 * (a / a_ref - 1.0), .kind = ErrorKind::percent,
                   .tolerance = 1});
  record_analytic({.case_name = drag, .quantity = "spin-up while sliding (rad/s²)", .closed_form = "f_s m g L / I",
                   .reference = w_ref, .measured = wdot, .error = 100 * (wdot / w_ref - 1.0),
                   .kind = ErrorKind::percent, .tolerance = 1});
  record_analytic({.case_name = drag, .quantity = "rolling speed (m/s)", .closed_form = "U / (1 + m L²/I) ≈ 2U/7",
                   .reference = v_ref, .measured = v_end, .error = 100 * (v_end / v_ref - 1.0),
                   .kind = ErrorKind::percent, .tolerance = 2});
  CHECK(std::abs(a / a_ref - 1.0) < 0.01);
  CHECK(std::abs(wdot / w_ref - 1.0) < 0.01);
  // 2 % on the rolling speed 4 ms after it starts rolling: the sphere has begun to climb the wall and gravity slows
  // it by about 5/7 g phi t ~ 0.2 %, and the tangential spring's damped oscillation around rolling adds a little.
  CHECK(std::abs(v_end / v_ref - 1.0) < 0.02);
}

namespace {

// Rows touching each wall and in all after one comparison of the two wall drivers.
struct WallDriverRound {
  std::vector<std::size_t> touching_per_wall;
  std::size_t touching = 0;
  double worst = 0.0;         // largest difference of a force or torque component, over its scale
  double worst_spring = 0.0;  // largest difference of a spring field, over the largest spring
};

// Both wall drivers on the same state from copies of the same wall springs: every component (x, y, z)
// of every owned row's wall force and wall torque, every spring and every touching flag. The README
// claims round-off agreement, to 1e-12 of the largest force and spring, not bit identity: the
// compiler fuses a*b+c in one driver and not in the other (-march=native), and the xsimd law takes
// its reciprocal square roots (spring turn, slider caps) from the 14-bit hardware estimate and two
// Newton steps, within a few ulp of the scalar twin's correctly rounded 1/sqrt. The largest effect
// is on the overlap, a difference of lengths (drum radius minus the centre's distance from the
// axis): one ulp of the 12 mm radius, 1.7e-18 m, is k_n x 1.7e-18 = 1.7e-15 N of force whatever the
// force itself, the size of the differences these rounds show (up to 2.3e-14 of the largest force,
// 0.13 N). The bound 1e-12 of the largest magnitude of any component over all rows (forces with
// forces, torques with torques) leaves a factor 40 above that and lies far below a lost or doubled
// wall term, a wrong lane or a wrong sign, which are O(1) of a contact force.
WallDriverRound compare_wall_drivers(gf::World& w) {
  Grains& g = w.grains;
  gf::WallHistory& live = g.extras.get<gf::WallHistory>();
  const gf::WallHistory saved = live;
  gf::Walls walls = w.resources.get<gf::Walls>();
  const auto& table = w.resources.get<gf::ContactTable>();
  const double t = w.clock.t;
  gf::compute_wall_forces<gf::LinearSpringDashpot>(g, walls, live, table, w.clock.dt, t);
  const gf::WallHistory h_simd = live;
  const std::size_t n = g.n_owned;
  auto copy = [n](const gf::ColumnD& c) {
    return std::vector<double>(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(n));
  };
  const std::vector<double> simd[6] = {copy(g.wall_force.x),  copy(g.wall_force.y),  copy(g.wall_force.z),
                                       copy(g.wall_torque.x), copy(g.wall_torque.y), copy(g.wall_torque.z)};
  live = saved;
  gf::compute_wall_forces_scalar<gf::LinearSpringDashpot>(g, walls, live, table, w.clock.dt, t);
  const gf::ColumnD* scalar[6] = {&g.wall_force.x,  &g.wall_force.y,  &g.wall_force.z,
                                  &g.wall_torque.x, &g.wall_torque.y, &g.wall_torque.z};
  const char* names[6] = {"force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z"};
  double fmax = 0.0, tmax = 0.0, smax = 0.0;
  WallDriverRound r;
  for (std::size_t i = 0; i < n; ++i) {
    bool any = false;
    for (int c = 0; c < 6; ++c) {
      const double v = std::abs((*scalar[c])[i]);
      (c < 3 ? fmax : tmax) = std::max(c < 3 ? fmax : tmax, v);
      any = any || (c < 3 && v != 0.0);
    }
    r.touching += any;
  }
  for (const auto& col : live.springs)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 6; ++k) smax = std::max(smax, std::abs(col[i].s[k]));
  REQUIRE(fmax > 0.0);
  REQUIRE(tmax > 0.0);
  REQUIRE(smax > 0.0);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 6; ++c) {
      const double d = std::abs(simd[c][i] - (*scalar[c])[i]);
      r.worst = std::max(r.worst, d / (c < 3 ? fmax : tmax));
      if (d <= 1e-12 * (c < 3 ? fmax : tmax)) continue;
      INFO("row " << i << " id " << g.pid.id[i] << " " << names[c] << ": xsimd " << simd[c][i] << ", scalar "
                  << (*scalar[c])[i] << ", largest " << (c < 3 ? fmax : tmax));
      REQUIRE(d <= 1e-12 * (c < 3 ? fmax : tmax));
    }
  REQUIRE(h_simd.springs.size() == live.springs.size());
  for (std::size_t q = 0; q < live.springs.size(); ++q)
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 6; ++k) {
        const double d = std::abs(h_simd.springs[q][i].s[k] - live.springs[q][i].s[k]);
        r.worst_spring = std::max(r.worst_spring, d / smax);
        if (d <= 1e-12 * smax) continue;
        INFO("wall " << q << ", row " << i << ", spring field " << k);
        REQUIRE(d <= 1e-12 * smax);
      }
  r.touching_per_wall.assign(live.active.size(), 0);
  for (std::size_t q = 0; q < live.active.size(); ++q)
    for (std::size_t i = 0; i < n; ++i) {
      REQUIRE(h_simd.active[q][i] == live.active[q][i]);
      r.touching_per_wall[q] += live.active[q][i] != 0;
    }
  // The world is left as the system would have left it: the live springs are the scalar driver's,
  // which equal the vector driver's to round-off.
  return r;
}

// The worst differences of the rounds of one wall-driver comparison, for analytic.csv.
void record_wall_drivers(const std::string& case_name, double worst, double worst_spring) {
  record_analytic({.case_name = case_name, .quantity = "force and torque components: largest difference / largest component",
                   .closed_form = "identical", .error = worst, .kind = ErrorKind::relative, .tolerance = 1e-12});
  record_analytic({.case_name = case_name, .quantity = "springs: largest difference / largest spring",
                   .closed_form = "identical", .error = worst_spring, .kind = ErrorKind::relative, .tolerance = 1e-12});
}

}  // namespace

TEST_CASE("wall contact: the xsimd driver equals the scalar driver on a stirred pack in a box", "[wall]") {
  // Grains pour onto the floor and hit the side walls, so rows enter, stay in and leave wall
  // contact between rounds.
  DemSimulation sim = DemSimulation::from_text(gf::test::binary_box_scene(3000, 100, 500.0));
  gf::test::stir_by_id(sim.grains(), 11);
  sim.prime();
  double worst = 0.0, worst_spring = 0.0;
  const int rounds = 6;
  for (int round = 0; round < rounds; ++round) {
    sim.advance(300);
    const WallDriverRound r = compare_wall_drivers(sim.world());
    REQUIRE(r.touching > 50);
    worst = std::max(worst, r.worst);
    worst_spring = std::max(worst_spring, r.worst_spring);
  }
  WARN("SIMD vs scalar wall driver, box: worst difference " << worst << " of the largest component, "
                                                            << worst_spring << " of the largest spring");
  record_wall_drivers("xsimd wall driver vs scalar, stirred binary pack in a box, " + std::to_string(rounds) + " states",
                      worst, worst_spring);
}

TEST_CASE("wall contact: the xsimd driver equals the scalar driver in a turning drum (cylinder and end walls)",
          "[wall][drum]") {
  // The small drum (24 mm across, 6 mm deep, turning at 3 rad/s about z) poured under strong gravity
  // and stirred, so the inner cylinder (its radial normal from a square root and a division per
  // lane, its surface moving under the contact points) and the two end planes all hold contacts.
  // The overlap limit is 0.5 of the diameter: 500 m/s^2 presses the soft seed-000 springs past 0.1
  // (these rounds compare drivers, not the pile's physics).
  DemSimulation sim = DemSimulation::from_text(gf::test::small_drum_scene(500.0, "max_overlap = 0.5\n"));
  gf::test::stir_by_id(sim.grains(), 13);
  sim.prime();
  const auto& walls = sim.world().resources.get<gf::Walls>().list;
  std::size_t cylinder = walls.size();
  for (std::size_t q = 0; q < walls.size(); ++q)
    if (walls[q].kind == gf::Wall::Kind::CylinderInner) cylinder = q;
  REQUIRE(cylinder < walls.size());
  REQUIRE(walls[cylinder].omega != 0.0);
  REQUIRE(sim.world().resources.get<gf::Walls>().rotation_enabled);
  std::size_t most_on_cylinder = 0;
  double worst = 0.0, worst_spring = 0.0;
  const int rounds = 6;
  for (int round = 0; round < rounds; ++round) {
    sim.advance(300);
    const WallDriverRound r = compare_wall_drivers(sim.world());
    INFO("round " << round << ": " << r.touching << " rows touch a wall, " << r.touching_per_wall[cylinder]
                  << " the cylinder");
    REQUIRE(r.touching > 20);
    most_on_cylinder = std::max(most_on_cylinder, r.touching_per_wall[cylinder]);
    worst = std::max(worst, r.worst);
    worst_spring = std::max(worst_spring, r.worst_spring);
  }
  WARN("SIMD vs scalar wall driver, drum: worst difference " << worst << " of the largest component, "
                                                            << worst_spring << " of the largest spring, up to "
                                                            << most_on_cylinder << " rows on the cylinder");
  record_wall_drivers("xsimd wall driver vs scalar, stirred pack in a turning drum, " + std::to_string(rounds) +
                          " states",
                      worst, worst_spring);
  // Once poured, a bed of 420 grains lies along the cylinder's lower arc.
  CHECK(most_on_cylinder > 30);
}

TEST_CASE("wall contact: rows that leave every wall keep no wall force, after a step and after priming", "[wall]") {
  // A row's wall force is summed anew at every evaluation; one that no longer reaches a wall must
  // not keep its last contact's force (the integrator would go on adding it). Rows pressed against
  // the floor and walls are moved to the middle of the box, 10 mm from every wall: each must then
  // read exactly zero, both after an ordinary evaluation and straight after a priming step on a
  // state with wall contacts (as a state read from a file is primed: it computes wall forces, then
  // restarts the springs and touch flags).
  auto centre_all = [](Grains& g) {
    for (std::size_t i = 0; i < g.n_owned; ++i) {
      g.pos.x[i] = 0.01;
      g.pos.y[i] = 0.015;
      g.pos.z[i] = 0.01;
    }
  };
  auto wall_sums = [](const Grains& g) {
    std::size_t loaded = 0;
    for (std::size_t i = 0; i < g.n_owned; ++i)
      loaded += g.wall_force.x[i] != 0.0 || g.wall_force.y[i] != 0.0 || g.wall_force.z[i] != 0.0 ||
                g.wall_torque.x[i] != 0.0 || g.wall_torque.y[i] != 0.0 || g.wall_torque.z[i] != 0.0;
    return loaded;
  };
  for (const bool reprimed : {true, false}) {
    INFO((reprimed ? "straight after priming" : "after 200 steps"));
    DemSimulation sim = DemSimulation::from_text(gf::test::binary_box_scene(3000, 100, 500.0));
    sim.prime();
    sim.advance(200);
    if (reprimed) sim.prime();
    gf::World& w = sim.world();
    Grains& g = w.grains;
    REQUIRE(wall_sums(g) > 50);
    centre_all(g);
    gf::compute_wall_forces<gf::LinearSpringDashpot>(g, w.resources.get<gf::Walls>(), g.extras.get<gf::WallHistory>(),
                                                     w.resources.get<gf::ContactTable>(), w.clock.dt, w.clock.t);
    CHECK(wall_sums(g) == 0);
    for (const auto& flags : g.extras.get<gf::WallHistory>().active)
      CHECK(std::count(flags.begin(), flags.begin() + static_cast<std::ptrdiff_t>(g.n_owned), std::uint8_t{1}) == 0);
  }
}
