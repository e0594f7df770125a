// A periodic liquid driven to a target mean velocity: the body force along the periodic axis is the
// control (the pressure gradient it stands for is rho times it), set at the start of every liquid step
// from the fluid nodes' mean velocity along that axis U_n. The last step's force f_{n-1} moved the mean by
// (U_n - U_{n-1}), so what the walls and grains took over that step is the loss
//   L = f_{n-1} - (U_n - U_{n-1}) / dt,
// and the force for this step covers it and closes a share r of the gap to the target:
//   f_n = L + r (U_target - U_n) / dt,
// which leaves U_{n+1} - U_target = (1 - r)(U_n - U_target) while the loss holds: the mean reaches the
// target in one step at r = 1 whatever the loss (gravity along a vertical pipe, the walls' shear, a bed's
// drag), and the force settles where it balances them: for a pipe's laminar flow Hagen-Poiseuille's
// 8 nu U / R^2 plus any gravity along the axis. The first step, with no last mean, takes L = f_0 (the
// scene's run.body_force). The plain integral form f_n = f_{n-1} + r (U_target - U_n)/dt gives, under a
// constant loss, e_{n+1} = (2 - r) e_n - e_{n-1} for the error e: at r = 1 an undamped oscillation of
// period 6 steps wherever the walls take little (a pipe of water swung by +-1e4 m/s^2 about its balance).
// OpenFOAM's meanVelocityForce reaches the same by correcting the velocity itself within the step.
// The force and the last mean are kept in checkpoints.
//
// Scene keys, [drive]: mean_velocity (m/s along the periodic axis, the superficial velocity over the
// fluid nodes' volume), relaxation (0 < r <= 1, default 1). Needs a geometry with a periodic axis.
// Reads FluidNodes (u, v, w, kind); writes LiquidParams::body_force along the axis and FlowDrive's last mean.
#pragma once

#include <limits>
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
  double last_mean = std::numeric_limits<double>::quiet_NaN();  // m/s, U at the last control step (none yet: NaN)
};

// [drive] of a liquid scene with params' periodicity read (none when the table is absent).
std::optional<FlowDrive> read_flow_drive(const SceneNode& root, const LiquidParams& params);

// The fluid nodes' mean velocity along `axis` (m/s; 0 without fluid nodes).
double mean_fluid_velocity(const FluidNodes& f, int axis);

// One control step: the body force along the drive's axis for the next step; d's last mean updated.
void drive_body_force(const FluidNodes& f, FlowDrive& d, LiquidParams& lp, double dt);

class DriveControl : public SystemBase<DriveControl> {
 public:
  using Reads = gf::Reads<FluidNodes>;
  using Writes = gf::Writes<LiquidParams, FlowDrive>;
  std::string_view name() const override { return "drive_control"; }
  void run(World& w, const StepContext& step) override;
};

}  // namespace gf
