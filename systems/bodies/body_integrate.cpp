#include "systems/bodies/body_integrate.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <string>

#include "engine/run_loop.hpp"

namespace gf {

namespace {

using Eigen::Quaterniond;
using Eigen::Vector3d;

Quaterniond orientation(const Bodies& b, std::size_t i) { return {b.q.w[i], b.q.x[i], b.q.y[i], b.q.z[i]}; }
Vector3d moments(const Bodies& b, std::size_t i) { return {b.inertia.i1[i], b.inertia.i2[i], b.inertia.i3[i]}; }
Vector3d omega(const Bodies& b, std::size_t i) { return {b.omega.x[i], b.omega.y[i], b.omega.z[i]}; }
Vector3d torque(const Bodies& b, std::size_t i) { return {b.torque.x[i], b.torque.y[i], b.torque.z[i]}; }

void store_omega(Bodies& b, std::size_t i, const Vector3d& w) { b.omega.x[i] = w.x(), b.omega.y[i] = w.y(), b.omega.z[i] = w.z(); }

// v += h (F/m + g); returns whether v is finite.
bool kick_velocity(Bodies& b, std::size_t i, const Gravity& g, double h) {
  const double a = h * b.mass.inv_m[i];
  b.vel.x[i] += a * b.force.x[i] + h * g.x;
  b.vel.y[i] += a * b.force.y[i] + h * g.y;
  b.vel.z[i] += a * b.force.z[i] + h * g.z;
  return std::isfinite(b.vel.x[i] + b.vel.y[i] + b.vel.z[i]);
}

// The body-frame angular momentum after a half kick: L = I R^T omega + h R^T tau.
Vector3d kicked_momentum(const Bodies& b, std::size_t i, const Quaterniond& q, double h) {
  const Quaterniond qt = q.conjugate();
  return moments(b, i).cwiseProduct(qt * omega(b, i)) + h * (qt * torque(b, i));
}

// The exact flow of L_k^2 / (2 I_k) for time t: the body turns about its own axis k by
// phi = t L_k / I_k, and L's body components, a fixed world vector seen from the body, by -phi.
void rotate_about_axis(Quaterniond& q, Vector3d& L, const Vector3d& I, int k, double t) {
  const double phi = t * L[k] / I[k];
  Vector3d axis = Vector3d::Zero();
  axis[k] = std::sin(0.5 * phi);
  q = q * Quaterniond(std::cos(0.5 * phi), axis.x(), axis.y(), axis.z());
  const int a = (k + 1) % 3, c = (k + 2) % 3;
  const double cs = std::cos(phi), sn = std::sin(phi), la = L[a], lc = L[c];
  L[a] = cs * la + sn * lc;
  L[c] = -sn * la + cs * lc;
}

// NO_SQUISH's free rotor (Miller et al. 2002, with one middle sub-step): symmetric, so the
// composite step is time-reversible and second order.
void free_rotation(Quaterniond& q, Vector3d& L, const Vector3d& I, double dt) {
  rotate_about_axis(q, L, I, 2, 0.5 * dt);
  rotate_about_axis(q, L, I, 1, 0.5 * dt);
  rotate_about_axis(q, L, I, 0, dt);
  rotate_about_axis(q, L, I, 1, 0.5 * dt);
  rotate_about_axis(q, L, I, 2, 0.5 * dt);
}

bool kick_drift_row(Bodies& b, std::size_t i, const Gravity& g, double dt) {
  if (!b.moving(i)) return true;  // fixed or removed: never moved (their velocities stay zero)
  const double h = 0.5 * dt;
  kick_velocity(b, i, g, h);
  b.pos.x[i] += dt * b.vel.x[i];
  b.pos.y[i] += dt * b.vel.y[i];
  b.pos.z[i] += dt * b.vel.z[i];
  Quaterniond q = orientation(b, i);
  Vector3d L = kicked_momentum(b, i, q, h);
  const Vector3d I = moments(b, i);
  free_rotation(q, L, I, dt);
  q.normalize();
  b.q.w[i] = q.w(), b.q.x[i] = q.x(), b.q.y[i] = q.y(), b.q.z[i] = q.z();
  const Vector3d w = q * L.cwiseQuotient(I);
  store_omega(b, i, w);
  return std::isfinite(b.pos.x[i] + b.pos.y[i] + b.pos.z[i] + w.sum() + q.coeffs().sum());
}

bool kick_row(Bodies& b, std::size_t i, const Gravity& g, double dt) {
  if (!b.moving(i)) return true;
  const double h = 0.5 * dt;
  const bool v_finite = kick_velocity(b, i, g, h);
  const Quaterniond q = orientation(b, i);
  const Vector3d w = q * kicked_momentum(b, i, q, h).cwiseQuotient(moments(b, i));
  store_omega(b, i, w);
  return v_finite && std::isfinite(w.sum());
}

template <class Row>
bool for_rows(Bodies& b, Row row) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, b.n, 256), true,
      [&](const tbb::blocked_range<std::size_t>& r, bool finite) {
        for (std::size_t i = r.begin(); i != r.end(); ++i) finite = row(i) && finite;
        return finite;
      },
      [](bool x, bool y) { return x && y; });
}

bool finite_row(const Bodies& b, std::size_t i) {
  return std::isfinite(b.pos.x[i] + b.pos.y[i] + b.pos.z[i] + b.vel.x[i] + b.vel.y[i] + b.vel.z[i] + b.omega.x[i] +
                       b.omega.y[i] + b.omega.z[i] + b.q.w[i] + b.q.x[i] + b.q.y[i] + b.q.z[i]);
}

// Names the first body whose state is not finite, with the step and the pass.
[[noreturn]] void report_nonfinite_body(const Bodies& b, const StepContext& step, const char* pass) {
  std::size_t row = 0;
  while (row < b.n && finite_row(b, row)) ++row;
  throw StabilityError("step " + std::to_string(step.step) + " (" + std::string(step.stage) + "): " + pass +
                       " left body row " + std::to_string(row) +
                       " with a non-finite state: its force or torque was not finite or too large for the step; "
                       "lower run.dt or check the body's mass and inertia");
}

}  // namespace

bool body_kick_drift(Bodies& b, const Gravity& g, double dt) {
  return for_rows(b, [&](std::size_t i) { return kick_drift_row(b, i, g, dt); });
}

bool body_kick(Bodies& b, const Gravity& g, double dt) {
  return for_rows(b, [&](std::size_t i) { return kick_row(b, i, g, dt); });
}

void IntegrateBodyPositions::run(World& world, const StepContext& step) {
  if (step.prime) return;
  Bodies& b = world.tables.get<Bodies>();
  if (!body_kick_drift(b, world.resources.get<Gravity>(), step.dt))
    report_nonfinite_body(b, step, "the bodies' opening half kick, drift and rotation");
}

void IntegrateBodyVelocities::run(World& world, const StepContext& step) {
  if (step.prime) return;
  Bodies& b = world.tables.get<Bodies>();
  if (!body_kick(b, world.resources.get<Gravity>(), step.dt))
    report_nonfinite_body(b, step, "the bodies' closing half kick");
}

}  // namespace gf
