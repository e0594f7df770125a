// Rigid-body integration (systems/bodies/body_integrate.hpp) against the torque-free top, the tumbling
// asymmetric top and free flight, run through the two systems as the step runs them.
#include "systems/bodies/body_integrate.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "engine/schedule.hpp"
#include "systems/bodies/bodies.hpp"

using Eigen::Quaterniond;
using Eigen::Vector3d;
using gf::BodyRow;

namespace {

constexpr double kPi = std::numbers::pi;

// A world holding one table of bodies and gravity, stepped by the two integrator systems with the
// forces and torques left as set (zero unless a test sets them).
struct Rig {
  gf::World world;
  gf::Bodies& bodies;
  gf::IntegrateBodyPositions positions;
  gf::IntegrateBodyVelocities velocities;
  std::int64_t steps = 0;

  explicit Rig(const Vector3d& g = Vector3d::Zero()) : bodies(world.tables.add<gf::Bodies>()) {
    world.resources.emplace<gf::Gravity>(gf::Gravity{g.x(), g.y(), g.z()});
  }
  void step(double dt) {
    const gf::StepContext ctx{steps * dt, dt, steps, 0, 1, false};
    positions.run(world, ctx);
    velocities.run(world, ctx);
    ++steps;
  }
  Quaterniond q(std::size_t i) const { return {bodies.q.w[i], bodies.q.x[i], bodies.q.y[i], bodies.q.z[i]}; }
  Vector3d omega(std::size_t i) const { return {bodies.omega.x[i], bodies.omega.y[i], bodies.omega.z[i]}; }
  Vector3d x(std::size_t i) const { return {bodies.pos.x[i], bodies.pos.y[i], bodies.pos.z[i]}; }
  Vector3d moments(std::size_t i) const { return {bodies.inertia.i1[i], bodies.inertia.i2[i], bodies.inertia.i3[i]}; }
  Vector3d omega_body(std::size_t i) const { return q(i).conjugate() * omega(i); }
  Vector3d momentum_world(std::size_t i) const { return q(i) * moments(i).cwiseProduct(omega_body(i)); }
  double energy(std::size_t i) const { return 0.5 * omega_body(i).dot(moments(i).cwiseProduct(omega_body(i))); }
};

// A body of unit mass at the origin turned by `frame`, spinning at body-frame w_body.
BodyRow spinning(const Vector3d& moments, const Vector3d& w_body, const Quaterniond& frame) {
  BodyRow row;
  row.mass = 1.0;
  row.inertia = {moments.x(), moments.y(), moments.z()};
  row.q = {frame.w(), frame.x(), frame.y(), frame.z()};
  const Vector3d w = frame * w_body;
  row.w = {w.x(), w.y(), w.z()};
  return row;
}

Quaterniond some_frame() {
  return Quaterniond(Eigen::AngleAxisd(0.9, Vector3d(1, 2, 3).normalized()));
}

// The precession rate of the body-frame angular velocity about axis 3 of a torque-free symmetric top,
// from the unwrapped angle of (w1, w2) over `periods` precession periods.
double precession_rate(double dt, double periods, const Vector3d& moments, double w3, double w_perp) {
  Rig rig;
  rig.bodies.push(spinning(moments, {w_perp, 0.0, w3}, some_frame()));
  const double omega = (moments.z() - moments.x()) / moments.x() * w3;
  const int steps = static_cast<int>(std::lround(periods * 2.0 * kPi / omega / dt));
  double angle = 0.0, last = 0.0;
  for (int k = 0; k < steps; ++k) {
    rig.step(dt);
    const Vector3d w = rig.omega_body(0);
    const double now = std::atan2(w.y(), w.x());
    angle += std::remainder(now - last, 2.0 * kPi);
    last = now;
  }
  return angle / (steps * dt);
}

}  // namespace

TEST_CASE("body_integrate: a torque-free symmetric top precesses at (I3 - I1) / I1 w3", "[bodies]") {
  // I1 = I2 = 2, I3 = 3 kg m^2, w3 = 10 rad/s, |w_perp| = 1 rad/s: Euler's equations turn (w1, w2)
  // about the symmetry axis at Omega = (I3 - I1) / I1 w3 = 5 rad/s (Landau and Lifshitz, Mechanics,
  // section 36). NO_SQUISH is second order, so the rate's error goes as dt^2: measured over 40 periods
  // (50 s) ... at dt = 1e-3 s and ... at 2e-3 s (ratio ...). Tolerance: 1e-4 of Omega at dt = 1e-3 s.
  const Vector3d moments(2.0, 2.0, 3.0);
  const double omega = (moments.z() - moments.x()) / moments.x() * 10.0;
  const double fine = precession_rate(1e-3, 40, moments, 10.0, 1.0);
  const double coarse = precession_rate(2e-3, 40, moments, 10.0, 1.0);
  const double err_fine = std::abs(fine / omega - 1.0), err_coarse = std::abs(coarse / omega - 1.0);
  CHECK(err_fine <= 1e-4);
  CHECK(err_coarse / err_fine == Approx(4.0).epsilon(0.1));
}

TEST_CASE("body_integrate: a tumbling asymmetric body conserves energy and angular momentum and flips", "[bodies]") {
  // I = (1, 2, 3) kg m^2 spun near the intermediate axis, w_body = (0.01, 1, 0.02) rad/s. L^2 > 2 E I2,
  // so (Landau and Lifshitz, section 37) w2 = A sn(tau, k) with tau = lambda t,
  // lambda^2 = (I3 - I2)(L^2 - 2 E I1) / (I1 I2 I3), k^2 = (I2 - I1)(2 E I3 - L^2) / ((I3 - I2)(L^2 - 2 E I1)):
  // w2 changes sign every 2 K(k) / lambda = 16.60 s, the intermediate-axis flip. Over ten flips
  // (33,200 steps of 5 ms, w dt = 5e-3):
  // - energy: NO_SQUISH is symplectic, so its error oscillates, O((w dt)^2), without drift: measured
  //   max |dE|/E = 2.3e-6 in the first flip and the same in the last; asserted below 1e-5 overall and
  //   the last flip's maximum within 10 % of the first's (no secular growth);
  // - world-frame angular momentum: each sub-step rotates L's body components and the body together,
  //   so L is conserved to round-off, which grows by at most an ulp or two for each of the nine
  //   rotations L passes through in a step (five plane rotations, four frame changes): asserted below
  //   16 eps |L| per step, measured 1.1e-11 of |L| over the run (1.4 eps per step);
  // - the flip: w2 changes sign at least ten times, at the analytic interval to 1e-4 (measured 4e-8;
  //   the scheme's error in a rate is O((w dt)^2) = 2.5e-5).
  const Vector3d I(1.0, 2.0, 3.0), w0(0.01, 1.0, 0.02);
  Rig rig;
  rig.bodies.push(spinning(I, w0, some_frame()));
  const double E0 = rig.energy(0);
  const Vector3d L0 = rig.momentum_world(0);
  const double L2 = L0.squaredNorm(), twoE = 2.0 * E0;
  const double lambda = std::sqrt((I.z() - I.y()) * (L2 - twoE * I.x()) / I.prod());
  const double k = std::sqrt((I.y() - I.x()) * (twoE * I.z() - L2) / ((I.z() - I.y()) * (L2 - twoE * I.x())));
  const double flip = 2.0 * std::comp_ellint_1(k) / lambda;
  const double dt = 5e-3;
  const int per_flip = static_cast<int>(flip / dt), steps = 10 * per_flip;
  double first_e = 0.0, last_e = 0.0, worst_e = 0.0, worst_l = 0.0, last = rig.omega_body(0).y();
  std::vector<double> crossings;
  for (int s = 0; s < steps; ++s) {
    rig.step(dt);
    const double e = std::abs(rig.energy(0) / E0 - 1.0);
    worst_e = std::max(worst_e, e);
    if (s < per_flip) first_e = std::max(first_e, e);
    if (s >= steps - per_flip) last_e = std::max(last_e, e);
    worst_l = std::max(worst_l, (rig.momentum_world(0) - L0).norm() / L0.norm());
    const double now = rig.omega_body(0).y();
    if ((now < 0) != (last < 0)) crossings.push_back((s + last / (last - now)) * dt);  // linear between steps
    last = now;
  }
  CHECK(worst_e <= 1e-5);
  CHECK(last_e <= 1.1 * first_e);
  CHECK(worst_l <= 16.0 * std::numeric_limits<double>::epsilon() * steps);
  REQUIRE(crossings.size() >= 10);
  const double mean = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  CHECK(mean == Approx(flip).epsilon(1e-4));
}

TEST_CASE("body_integrate: free flight under gravity follows the parabola to round-off", "[bodies]") {
  // Velocity Verlet is exact for a constant acceleration, and the spin (about no principal axis) does
  // not touch the translation. Round-off: a few ulps of the position per step, so the bound is
  // 4 eps max|x| per step (measured 6.5e-13 m after 2,000 steps, |x| up to 20 m: 0.07 of the bound).
  const Vector3d g(0.3, -9.81, 0.1), x0(1.0, 2.0, -0.5), v0(0.7, 3.0, -1.2);
  Rig rig(g);
  BodyRow row = spinning({1.0, 2.0, 3.0}, {3.0, -2.0, 5.0}, some_frame());
  row.x = {x0.x(), x0.y(), x0.z()};
  row.v = {v0.x(), v0.y(), v0.z()};
  rig.bodies.push(row);
  const double dt = 1e-3, eps = std::numeric_limits<double>::epsilon();
  const int steps = 2000;
  double worst = 0.0, reach = 0.0;
  for (int s = 1; s <= steps; ++s) {
    rig.step(dt);
    const double t = s * dt;
    const Vector3d exact = x0 + v0 * t + 0.5 * g * t * t;
    worst = std::max(worst, (rig.x(0) - exact).norm());
    reach = std::max(reach, exact.norm());
  }
  CHECK(worst <= 4.0 * eps * reach * steps);
}

TEST_CASE("body_integrate: torques turn bodies as the closed forms say, to round-off", "[bodies]") {
  // About a principal axis a constant torque gives the angle alpha t^2 / 2 exactly: the kicks make the
  // half-step angular velocities exact and the rotation about a principal axis is exact. On a tumbling
  // asymmetric body the world-frame angular momentum grows exactly as L0 + tau t: the kicks add
  // tau dt / 2 in the world frame (through R^T, whatever the orientation) and the free rotation keeps
  // L. Round-off bounds: 4 eps per step for the quaternion (|q| = 1), 16 eps |L| per step for the
  // momentum as in the tumbling test (measured after 4,000 steps: 2.3e-13, 0.06 of its bound, and
  // 8.9e-12 kg m^2/s with |L| up to 4.3, 0.15 of its bound).
  const double dt = 1e-3, eps = std::numeric_limits<double>::epsilon();
  const int steps = 4000;
  const Quaterniond frame = some_frame();
  Rig rig;
  rig.bodies.push(spinning({1.0, 2.0, 4.0}, Vector3d::Zero(), frame));
  rig.bodies.push(spinning({1.0, 2.0, 3.0}, {0.3, 2.0, -0.5}, frame));
  const Vector3d axis = frame * Vector3d::UnitZ(), tau = 2.0 * axis;  // alpha = 0.5 rad/s^2 on body 0
  const Vector3d tau1(0.4, -0.3, 0.8), L0 = rig.momentum_world(1);
  rig.bodies.torque.x[0] = tau.x(), rig.bodies.torque.y[0] = tau.y(), rig.bodies.torque.z[0] = tau.z();
  rig.bodies.torque.x[1] = tau1.x(), rig.bodies.torque.y[1] = tau1.y(), rig.bodies.torque.z[1] = tau1.z();
  double worst_q = 0.0, worst_l = 0.0, reach = 0.0;
  for (int s = 1; s <= steps; ++s) {
    rig.step(dt);
    const double t = s * dt;
    const Quaterniond expected = Quaterniond(Eigen::AngleAxisd(0.25 * t * t, axis)) * frame;
    worst_q = std::max(worst_q, (rig.q(0).coeffs() - expected.coeffs()).norm());
    worst_l = std::max(worst_l, (rig.momentum_world(1) - (L0 + tau1 * t)).norm());
    reach = std::max(reach, (L0 + tau1 * t).norm());
  }
  CHECK(worst_q <= 4.0 * eps * steps);
  CHECK(worst_l <= 16.0 * eps * reach * steps);
}

TEST_CASE("body_integrate: members are placed at x + R(q) c in the scheduled step", "[bodies]") {
  gf::World world;
  gf::Bodies& bodies = world.tables.add<gf::Bodies>();
  gf::Members& members = world.tables.add<gf::Members>();
  world.resources.emplace<gf::Gravity>(gf::Gravity{0.0, -9.81, 0.0});
  BodyRow row = spinning({1.0, 2.0, 3.0}, {0.5, -1.0, 2.0}, some_frame());
  row.v = {1.0, 0.0, 0.0};
  bodies.push(row);
  members.push({0, {{0.1, 0.0, 0.0}, {0.3, 0.0, 0.0}, {0.2, 0.1, 0.0}, {0.2, 0.0, 0.1}}, 0.05});
  members.push({0, {{-0.4, 0.2, 0.0}}, 0.1});
  gf::Schedule schedule;
  schedule.emplace<gf::IntegrateBodyPositions>();
  schedule.emplace<gf::PlaceMembers>();
  schedule.emplace<gf::IntegrateBodyVelocities>();
  schedule.build(world);
  for (int s = 0; s < 10; ++s) schedule.run_step({s * 1e-3, 1e-3, s, 0, 1, false});
  const Quaterniond q(bodies.q.w[0], bodies.q.x[0], bodies.q.y[0], bodies.q.z[0]);
  const Vector3d x(bodies.pos.x[0], bodies.pos.y[0], bodies.pos.z[0]);
  CHECK(members.bound.cx[0] == Approx(0.2).epsilon(1e-15));
  CHECK(members.bound.radius[0] == Approx(std::sqrt(0.01125) + 0.05).epsilon(1e-15));
  CHECK(members.bound.radius[1] == 0.1);
  for (std::size_t m = 0; m < 2; ++m) {
    const Vector3d c = x + q * Vector3d(members.bound.cx[m], members.bound.cy[m], members.bound.cz[m]);
    CHECK((Vector3d(members.centre.x[m], members.centre.y[m], members.centre.z[m]) - c).norm() <= 1e-15);
  }
  CHECK(bodies.pos.x[0] == Approx(1e-2).epsilon(1e-12));
}
