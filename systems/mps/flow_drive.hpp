// A periodic liquid driven to a target mean velocity: the body force along the periodic axis is the
// control (the pressure gradient it stands for is rho times it), set at the start of every liquid step
// from the fluid nodes' mean velocity along that axis (OpenFOAM's meanVelocityForce does the same):
//   f <- f + relaxation (U_target - U_mean) / dt.
// The body force acts on every fluid node alike, so with relaxation 1 it restores the mean velocity
// the last step lost to the walls (and to grains, in a coupled run) within one step; the force then
// settles where it balances them: for a pipe's laminar flow Hagen-Poiseuille's 8 nu U / R^2, for a
// packed or fluidised bed the bed's pressure gradient over rho. Lower relaxation damps the force's
// step-to-step noise. The force starts from the scene's run.body_force and is kept in checkpoints.
//
// Scene keys, [drive]: mean_velocity (m/s along the periodic axis, the superficial velocity over the
// fluid nodes' volume), relaxation (0 < r <= 1, default 1). Needs a geometry with a periodic axis.
// Reads FluidNodes (u, v, w, kind); writes LiquidParams::body_force along the axis.
#pragma once

#include <optional>

#include "engine/scene.hpp"
#include "engine/system.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"

namespace gf {

struct FlowDrive {
  int axis = 0;             // the periodic axis
  double target = 0.0;      // m/s
  double relaxation = 1.0;
};

// [drive] of a liquid scene with params' periodicity read (none when the table is absent).
std::optional<FlowDrive> read_flow_drive(const SceneNode& root, const LiquidParams& params);

// The fluid nodes' mean velocity along `axis` (m/s; 0 without fluid nodes).
double mean_fluid_velocity(const FluidNodes& f, int axis);

// One control step: the body force along the drive's axis moved towards the target.
void drive_body_force(const FluidNodes& f, const FlowDrive& d, LiquidParams& lp, double dt);

class DriveControl : public SystemBase<DriveControl> {
 public:
  using Reads = gf::Reads<FluidNodes, FlowDrive>;
  using Writes = gf::Writes<LiquidParams>;
  std::string_view name() const override { return "drive_control"; }
  void run(World& w, const StepContext& step) override;
};

}  // namespace gf
