// Velocity Verlet for translation and spin (symplectic; exact energy balance for e = 1 up to the
// O(dt^2) shadow-Hamiltonian oscillation). A step is:
//   integrate_positions:  v += dt/2 a(t), w += dt/2 alpha(t), x += dt v
//   (broadphase, contacts at t + dt)
//   integrate_velocities: v += dt/2 a(t + dt), w += dt/2 alpha(t + dt)
// with a = (sum of the declared force terms)/m + g and alpha = (sum of the torque terms)/I (spheres:
// I isotropic); force_terms.hpp says how a system declares a term. The terms are added in the order
// declared, so the sum, and the run, do not depend on anything else.
#pragma once

#include "engine/system.hpp"
#include "systems/integrate/force_terms.hpp"

namespace gf {

struct Gravity {
  double x = 0, y = 0, z = 0;  // m/s^2
};

// Both return whether every value they wrote is finite (checked in the same pass).
bool kick(Grains& g, const ForceTerms& terms, const Gravity& grav, double half_dt);
// The kick, then x += dt v with the kicked velocity, in one pass (integrate_positions' work).
bool kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double half_dt, double dt);

// The accesses of an integrator: it reads mass, gravity and every term, writes `Writes`.
Access integrator_access(const ForceTerms& terms, Access writes);

// Kick and drift at the start of the step (a priming pass, which only computes forces, skips it).
class IntegratePositions : public System {
 public:
  explicit IntegratePositions(ForceTerms terms) : terms_(std::move(terms)) {}
  std::string_view name() const override { return "integrate_positions"; }
  Access access() const override;
  void run(World& world, const StepContext& step) override;

 private:
  ForceTerms terms_;
};

// The closing kick with the forces of the step's end.
class IntegrateVelocities : public System {
 public:
  explicit IntegrateVelocities(ForceTerms terms) : terms_(std::move(terms)) {}
  std::string_view name() const override { return "integrate_velocities"; }
  Access access() const override;
  void run(World& world, const StepContext& step) override;

 private:
  ForceTerms terms_;
};

}  // namespace gf
