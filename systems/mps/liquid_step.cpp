#include "systems/mps/liquid_step.hpp"

#include "systems/mps/boundaries.hpp"
#include "systems/mps/collision.hpp"
#include "systems/mps/explicit_step.hpp"
#include "systems/mps/mixing_length.hpp"
#include "systems/mps/flow_drive.hpp"
#include "systems/mps/free_surface.hpp"
#include "systems/mps/liquid_fraction.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/number_density.hpp"
#include "systems/mps/ppe.hpp"
#include "systems/mps/pressure_gradient.hpp"

namespace gf {

namespace {

template <class R>
R& res(World& w) {
  return w.resources.get<R>();
}
FluidNodes& nodes(World& w) { return w.tables.get<FluidNodes>(); }

struct NeighborSearch : SystemBase<NeighborSearch> {
  using Reads = gf::Reads<LiquidParams>;
  using Writes = gf::Writes<FluidNodes, NeighborPairs>;
  std::string_view name() const override { return "neighbour_search"; }
  void run(World& w, const StepContext& step) override {
    auto& f = nodes(w);
    auto& lp = res<LiquidParams>(w);
    NeighborPairs& nb = res<NeighborPairs>(w);
    if (!neighbors_stale(f, nb, lp.skin, step.dt)) return;
    wrap_periodic(f, lp.periodic);
    build_neighbors(f, lp.k.re + lp.skin, lp.periodic, nb);
  }
};

struct NumberDensity : SystemBase<NumberDensity> {
  using Reads = gf::Reads<LiquidParams>;
  using Writes = gf::Writes<FluidNodes, NeighborPairs>;
  std::string_view name() const override { return "number_density"; }
  void run(World& w, const StepContext&) override { compute_number_density(nodes(w), res<NeighborPairs>(w), res<LiquidParams>(w).k.re); }
};

struct ExplicitStep : SystemBase<ExplicitStep> {
  using Reads = gf::Reads<LiquidParams, NeighborPairs, LiquidFraction>;
  using Writes = gf::Writes<FluidNodes, EddyViscosity>;
  std::string_view name() const override { return "explicit_step"; }
  void run(World& w, const StepContext& step) override {
    const LiquidParams& lp = res<LiquidParams>(w);
    std::span<const double> nut;
    if (lp.mixing_length.on) {
      EddyViscosity& e = res<EddyViscosity>(w);
      mixing_length_viscosity(nodes(w), res<NeighborPairs>(w), lp, e.nut);
      nut = e.nut;
    }
    predict_velocity(nodes(w), res<NeighborPairs>(w), lp, step.dt, liquid_fraction_of(w), nut);
  }
};

struct PredictedDensity : SystemBase<PredictedDensity> {
  using Reads = gf::Reads<LiquidParams, StabilityLimits>;
  using Writes = gf::Writes<FluidNodes, NeighborPairs, LiquidDiagnostics>;
  std::string_view name() const override { return "predicted_density"; }
  void run(World& w, const StepContext& step) override {
    auto& f = nodes(w);
    auto& lp = res<LiquidParams>(w);
    compute_number_density(f, res<NeighborPairs>(w), lp.k.re);
    check_density(f, lp, res<StabilityLimits>(w), step.t + step.dt, res<LiquidDiagnostics>(w));
  }
};

struct FreeSurface : SystemBase<FreeSurface> {
  using Reads = gf::Reads<LiquidParams, LiquidFraction>;
  using Writes = gf::Writes<FluidNodes, LiquidDiagnostics>;
  std::string_view name() const override { return "free_surface"; }
  void run(World& w, const StepContext&) override {
    res<LiquidDiagnostics>(w).surface_nodes = detect_free_surface(nodes(w), res<LiquidParams>(w), liquid_fraction_of(w));
  }
};

struct PressureSolve : SystemBase<PressureSolve> {
  using Reads = gf::Reads<LiquidParams, NeighborPairs, LiquidFraction>;
  using Writes = gf::Writes<FluidNodes, PpeWorkspace, LiquidDiagnostics>;
  std::string_view name() const override { return "pressure_solve"; }
  void run(World& w, const StepContext& step) override {
    auto& lp = res<LiquidParams>(w);
    auto& d = res<LiquidDiagnostics>(w);
    d.ppe = solve_pressure(nodes(w), res<NeighborPairs>(w), lp, step.dt, res<PpeWorkspace>(w), liquid_fraction_of(w));
    ++d.ppe_solves;
    d.ppe_iterations_total += static_cast<double>(d.ppe.iterations);
    check_ppe(d.ppe, lp.solver, step.t + step.dt);
  }
};

struct DummyPressure : SystemBase<DummyPressure> {
  using Reads = gf::Reads<LiquidParams, NeighborPairs>;
  using Writes = gf::Writes<FluidNodes>;
  std::string_view name() const override { return "dummy_pressure"; }
  void run(World& w, const StepContext&) override { extrapolate_dummy_pressure(nodes(w), res<NeighborPairs>(w), res<LiquidParams>(w)); }
};

struct PressureCorrect : SystemBase<PressureCorrect> {
  using Reads = gf::Reads<LiquidParams, NeighborPairs>;
  using Writes = gf::Writes<FluidNodes>;
  std::string_view name() const override { return "pressure_correct"; }
  void run(World& w, const StepContext& step) override { correct_velocity(nodes(w), res<NeighborPairs>(w), res<LiquidParams>(w), step.dt); }
};

struct Collision : SystemBase<Collision> {
  using Reads = gf::Reads<LiquidParams, NeighborPairs>;
  using Writes = gf::Writes<FluidNodes>;
  std::string_view name() const override { return "collision"; }
  void run(World& w, const StepContext& step) override {
    apply_collisions(nodes(w), res<NeighborPairs>(w), res<LiquidParams>(w).collision, step.dt);
  }
};

struct MotionCheck : SystemBase<MotionCheck> {
  using Reads = gf::Reads<FluidNodes, LiquidParams, StabilityLimits>;
  using Writes = gf::Writes<LiquidDiagnostics>;
  std::string_view name() const override { return "motion_check"; }
  void run(World& w, const StepContext& step) override {
    check_motion(nodes(w), res<LiquidParams>(w), res<StabilityLimits>(w), step.dt, step.t + step.dt,
                 res<LiquidDiagnostics>(w));
  }
};

}  // namespace

void schedule_liquid_step(Schedule& step, bool drive) {
  if (drive) step.emplace<DriveControl>();
  step.emplace<NeighborSearch>();
  step.emplace<NumberDensity>();
  step.emplace<ExplicitStep>();
  step.emplace<PredictedDensity>();
  step.emplace<FreeSurface>();
  step.emplace<PressureSolve>();
  step.emplace<DummyPressure>();
  step.emplace<PressureCorrect>();
  step.emplace<Collision>();
  step.emplace<MotionCheck>();
}

}  // namespace gf
