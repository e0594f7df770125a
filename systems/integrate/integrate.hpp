// Velocity Verlet for translation and spin (symplectic; exact energy balance for e = 1 up to the
// O(dt^2) shadow-Hamiltonian oscillation). A step is:
//   integrate_positions:  v += dt/2 a(t), w += dt/2 alpha(t), x += dt v
//   (broadphase, contacts at t + dt)
//   integrate_velocities: v += dt/2 a(t + dt), w += dt/2 alpha(t + dt)
// with a = (F_pair + F_wall)/m + g and alpha = (T_pair + T_wall)/I (spheres: I isotropic).
#pragma once

#include "engine/system.hpp"

namespace gf {

struct Gravity {
  double x = 0, y = 0, z = 0;  // m/s^2
};

// A priming pass computes the forces of the initial state without moving anything, so the first
// half-kick uses a(0) rather than zero.
struct StepMode {
  bool prime = false;
};

void kick(Grains& g, const Gravity& grav, double half_dt);
// The kick, then x += dt v with the kicked velocity, in one pass (integrate_positions' work).
void kick_drift(Grains& g, const Gravity& grav, double half_dt, double dt);

class IntegratePositions : public SystemBase<IntegratePositions> {
 public:
  using Reads = gf::Reads<Force, Torque, WallForce, WallTorque, Mass, Gravity, Clock, StepMode>;
  using Writes = gf::Writes<Position, Velocity, AngularVelocity>;
  std::string_view name() const override { return "integrate_positions"; }
  void run(World& world) override;
};

class IntegrateVelocities : public SystemBase<IntegrateVelocities> {
 public:
  using Reads = gf::Reads<Force, Torque, WallForce, WallTorque, Mass, Gravity, Clock, StepMode>;
  using Writes = gf::Writes<Velocity, AngularVelocity>;
  std::string_view name() const override { return "integrate_velocities"; }
  void run(World& world) override;
};

}  // namespace gf
