// Particle-wall contacts, a template on the contact law (laws.hpp), with the law's constants for
// a species against a wall (for seed 000's law: the particle's own mass and inertia in the
// damping, Table 2). Geometry from sphere_geometry.hpp (lever arm L = r - delta/2 as for pairs).
// Two drivers share the law: an xsimd one over batches of rows (the default) and its scalar twin,
// kept as the reference the tests compare it with.
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, ContactTable.
// Writes: WallForce, WallTorque, WallHistory, Walls (the current geometry and each wall's load).
#pragma once


#include "engine/system.hpp"
#include "systems/contact/contact_table.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/stability/stability_report.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// Throws StabilityError naming the grain deepest in a wall past `limit` (run.max_overlap), the wall,
// the step and the fix.
[[noreturn]] void report_wall_overlap(const Grains& g, const Walls& walls, double limit, const StepContext& step);

// Sums every wall's force and torque on each owned row into WallForce/WallTorque; the walls are
// placed at time t_contact (the time the positions refer to). Instantiated for every law of
// ContactLaws. Returns whether some wall overlap passed overlap_limit of the grain's diameter
// (run.max_overlap, at most 1; found in the same pass).
template <class L>
bool compute_wall_forces(Grains& g, Walls& walls, WallHistory& history, const ContactTable& table, double dt,
                         double t_contact, double overlap_limit = 1.0);
template <class L>
bool compute_wall_forces_scalar(Grains& g, Walls& walls, WallHistory& history, const ContactTable& table, double dt,
                                double t_contact, double overlap_limit = 1.0);

// The integrator's term this system fills.
inline ForceTerm wall_force_term() { return force_term<WallForce, WallTorque>("wall_contact"); }

template <class L>
class WallContact : public SystemBase<WallContact<L>> {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, ContactTable, OverlapLimit>;
  using Writes = gf::Writes<WallForce, WallTorque, WallHistory, Walls>;  // Walls: current geometry
  std::string_view name() const override { return "wall_contact"; }
  void run(World& world, const StepContext& step) override {
    // Positions were advanced by the first half of the step: they refer to t + dt.
    const double t = step.t + (step.prime ? 0.0 : step.dt);
    const double limit = world.resources.get<OverlapLimit>().ratio;
    Walls& walls = world.resources.get<Walls>();
    if (compute_wall_forces<L>(world.grains, walls, world.grains.extras.get<WallHistory>(),
                               world.resources.get<ContactTable>(), step.dt, t, limit))
      report_wall_overlap(world.grains, walls, limit, step);
    if (!step.prime) walls.loads.accumulate();
  }
};

}  // namespace gf
