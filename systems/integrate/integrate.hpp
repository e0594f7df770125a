// Velocity Verlet for translation and spin (symplectic; exact energy balance for e = 1 up to the
// O(dt^2) shadow-Hamiltonian oscillation). A step is:
//   integrate_positions:  v += dt/2 a(t), w += dt/2 alpha(t), x += dt v
//   (broadphase, contacts at t + dt)
//   integrate_velocities: v += dt/2 a(t + dt), w += dt/2 alpha(t + dt)
// with a = (sum of the declared force terms)/m + g and alpha = (sum of the torque terms)/I (spheres:
// I isotropic); force_terms.hpp says how a system declares a term. The terms are added in the order
// declared, so the sum, and the run, do not depend on anything else.
// When nothing reads the state between two steps (StepContext::observed false), the closing kick may
// be deferred: the next opening pass then applies both half-kicks with the same forces,
// v = (v + h a) + h a, and drifts, in one pass over the columns instead of two, the same arithmetic
// (the run is bit for bit the same). Schedule::complete applies a kick still pending.
#pragma once

#include <memory>

#include "engine/system.hpp"
#include "systems/integrate/force_terms.hpp"

namespace gf {

struct Gravity {
  double x = 0, y = 0, z = 0;  // m/s^2
};

// All three return whether every value they wrote is finite (checked in the same pass).
bool kick(Grains& g, const ForceTerms& terms, const Gravity& grav, double half_dt);
// The kick, then x += dt v with the kicked velocity, in one pass (integrate_positions' work).
bool kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double half_dt, double dt);
// A kick of first_half_dt (the deferred closing kick), then kick_drift, in one pass.
bool kick_kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double first_half_dt, double half_dt,
                     double dt);

// A closing kick left to the next opening pass, shared by the two integrators of one schedule.
struct DeferredKick {
  bool pending = false;
  StepContext step;  // the step whose closing kick it is (for a report)
};

// The accesses of an integrator: it reads mass, gravity and every term, writes `Writes`.
Access integrator_access(const ForceTerms& terms, Access writes);

// Kick and drift at the start of the step (a priming pass, which only computes forces, skips it).
// With `deferred`, it first applies a closing kick the last step left.
class IntegratePositions : public System {
 public:
  explicit IntegratePositions(ForceTerms terms, std::shared_ptr<DeferredKick> deferred = nullptr)
      : terms_(std::move(terms)), deferred_(std::move(deferred)) {}
  std::string_view name() const override { return "integrate_positions"; }
  Access access() const override;
  void run(World& world, const StepContext& step) override;

 private:
  ForceTerms terms_;
  std::shared_ptr<DeferredKick> deferred_;
};

// The closing kick with the forces of the step's end. With `deferred` (shared with the schedule's
// IntegratePositions, which must come first in the next step with nothing between that changes
// rows or forces), a step that nobody observes leaves it to the next opening pass.
class IntegrateVelocities : public System {
 public:
  explicit IntegrateVelocities(ForceTerms terms, std::shared_ptr<DeferredKick> deferred = nullptr)
      : terms_(std::move(terms)), deferred_(std::move(deferred)) {}
  std::string_view name() const override { return "integrate_velocities"; }
  Access access() const override;
  void run(World& world, const StepContext& step) override;
  void complete(World& world) override;

 private:
  ForceTerms terms_;
  std::shared_ptr<DeferredKick> deferred_;
};

}  // namespace gf
