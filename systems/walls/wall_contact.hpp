// Particle-wall contacts with the same linear spring-dashpot-slider law, with the particle's own
// mass and inertia in the damping (seed 000, Table 2). Lever arm L = r - delta/2 as for pairs.
// Two drivers share the law: an xsimd one over batches of rows (the default) and its scalar twin,
// kept as the reference the tests compare it with.
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, ContactTable, Clock, StepMode.
// Writes: WallForce, WallTorque, WallHistory, Walls (the current, rotated geometry).
#pragma once

#include "engine/system.hpp"
#include "systems/contact/contact_params.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// Sums every wall's force and torque on each owned row into WallForce/WallTorque; the walls are
// placed at time t_contact (the time the positions refer to).
void compute_wall_forces(Grains& g, Walls& walls, WallHistory& history, const ContactTable& table, double dt,
                         double t_contact);
void compute_wall_forces_scalar(Grains& g, Walls& walls, WallHistory& history, const ContactTable& table, double dt,
                                double t_contact);

class WallContact : public SystemBase<WallContact> {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, ContactTable, Clock, StepMode>;
  using Writes = gf::Writes<WallForce, WallTorque, WallHistory, Walls>;  // Walls: current geometry
  std::string_view name() const override { return "wall_contact"; }
  void run(World& world) override;
};

}  // namespace gf
