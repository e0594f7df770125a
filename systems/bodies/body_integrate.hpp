// Rigid-body integration of the Bodies table: velocity Verlet for the centre of mass, as for the
// spheres (systems/integrate/integrate.hpp), and the NO_SQUISH splitting for the rotation (Miller,
// Eleftheriou, Pattnaik, Ndirango, Newns, Martyna 2002, J. Chem. Phys. 116, 8649). A step is
//   integrate_body_positions:   v += h (F/m + g), x += dt v;
//                               L += h R^T tau (body-frame angular momentum, R = R(q));
//                               free rotation by dt: R3(dt/2) R2(dt/2) R1(dt) R2(dt/2) R3(dt/2);
//                               q renormalised; omega = R I^-1 L
//   (members placed, contacts at t + dt)
//   integrate_body_velocities:  v += h (F/m + g), L += h R^T tau, omega = R I^-1 L
// with h = dt/2, I the principal moments and Rk(t) the exact flow of the free rotor's part
// L_k^2 / (2 I_k): the body turns about its own axis k by t L_k / I_k (q <- q (cos, sin e_k)) while
// the body-frame components of the fixed world-frame L turn back by the same angle. (Miller et al.
// carry the conjugate quaternion momentum P = 2 S(q) (0, L) instead of L: the same sub-flows.)
// Why NO_SQUISH (also LAMMPS' fix rigid/nve): each sub-step is an exact rotation, so the scheme is
// symplectic and time-reversible (the energy error stays bounded, O(dt^2), without secular drift,
// which the Richardson-style quaternion update of LAMMPS' fix rigid and LIGGGHTS' rigid-body fixes,
// not symplectic, does not promise); the world-frame angular momentum of a torque-free body is
// conserved to round-off (every sub-step turns L's body components and the body together); the
// quaternion stays unit up to round-off (renormalised each step anyway); it needs a sine and a cosine
// per sub-step and no iteration (unlike implicit midpoint updates); and the torque enters as half
// kicks like the force, so the step is velocity Verlet's: exact for a constant force, and for a
// constant torque about a principal axis (tests/body_integrate_test.cpp).
// Angular velocity is stored in the world frame (what contacts read); the body-frame L is rebuilt
// from it each half step, L = I R^T omega, exact to round-off.
// Only moving bodies are integrated: fixed and removed ones (BodyMotion) keep their pose and zero
// velocities whatever force their members feel.
#pragma once

#include <cstddef>

#include "engine/system.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/integrate/integrate.hpp"

namespace gf {

// Both return whether every position (kick_drift) or velocity and angular velocity (kick) they wrote
// is finite. dt is the whole step.
bool body_kick_drift(Bodies& b, const Gravity& g, double dt);
bool body_kick(Bodies& b, const Gravity& g, double dt);

// The opening half kick, the drift and the free rotation (a priming pass, which only computes forces,
// skips it).
class IntegrateBodyPositions : public SystemBase<IntegrateBodyPositions> {
 public:
  using Reads = gf::Reads<BodyMass, BodyInertia, BodyForce, BodyTorque, BodyMotion, Gravity>;
  using Writes = gf::Writes<BodyPosition, BodyOrientation, BodyVelocity, BodyAngularVelocity>;
  std::string_view name() const override { return "integrate_body_positions"; }
  void run(World& world, const StepContext& step) override;
};

// The closing half kick with the force and torque of the step's end.
class IntegrateBodyVelocities : public SystemBase<IntegrateBodyVelocities> {
 public:
  using Reads = gf::Reads<BodyOrientation, BodyMass, BodyInertia, BodyForce, BodyTorque, BodyMotion, Gravity>;
  using Writes = gf::Writes<BodyVelocity, BodyAngularVelocity>;
  std::string_view name() const override { return "integrate_body_velocities"; }
  void run(World& world, const StepContext& step) override;
};

}  // namespace gf
