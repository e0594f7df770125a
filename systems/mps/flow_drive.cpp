#include "systems/mps/flow_drive.hpp"

#include <cmath>

#include "systems/mps/liquid_fields.hpp"

namespace gf {

std::optional<FlowDrive> read_flow_drive(const SceneNode& root, const LiquidParams& params) {
  const auto t = root.maybe_table("drive");
  if (!t) return std::nullopt;
  if (params.periodic.axis < 0)
    t->fail("mean_velocity", "a mean velocity is driven along a periodic axis, and the geometry has none",
            "use a geometry with a periodic axis (type = \"channel\" or \"pipe\"), or remove [drive]");
  FlowDrive d;
  d.axis = params.periodic.axis;
  d.target = read_number(*t, kDriveFields.field("mean_velocity"));
  d.relaxation = read_number(*t, kDriveFields.field("relaxation"));
  return d;
}

double mean_fluid_velocity(const FluidNodes& f, int axis) {
  const ColumnD& u = axis == 0 ? f.u : axis == 1 ? f.v : f.w;
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid) sum += u[i], ++n;
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

void drive_body_force(const FluidNodes& f, FlowDrive& d, LiquidParams& lp, double dt) {
  double& force = lp.body_force[static_cast<std::size_t>(d.axis)];
  const double mean = mean_fluid_velocity(f, d.axis);
  const double loss = std::isnan(d.last_mean) ? force : force - (mean - d.last_mean) / dt;
  force = loss + d.relaxation * (d.target - mean) / dt;
  d.last_mean = mean;
}

void DriveControl::run(World& w, const StepContext& step) {
  if (step.prime) return;  // no time passes
  drive_body_force(w.tables.get<FluidNodes>(), w.resources.get<FlowDrive>(), w.resources.get<LiquidParams>(), step.dt);
}

}  // namespace gf
