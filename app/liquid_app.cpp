// `grainflow run` and `grainflow check` for MPS liquid scenes, with the DEM side's conventions: series.csv
// flushed per row, VTK frames with a .pvd index, summary.json rewritten atomically at start and end, exit code 3
// and status "failed" when a stability detector stops the run, checkpoints in checkpoints/checkpoint.gfc
// (output.checkpoint_interval, at the end unless output.checkpoint_at_end = false) and `--resume` continuing a
// run bit-identically to the same end step.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/run_model.hpp"
#include "app/run_outcome.hpp"
#include "systems/mps/liquid_checkpoint.hpp"
#include "systems/mps/liquid_observables.hpp"
#include "systems/mps/liquid_outputs.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/output/checkpoint_output.hpp"

namespace gf {

namespace {

const char* geometry_name(LiquidGeometry::Kind k) {
  switch (k) {
    case LiquidGeometry::Kind::Box: return "box";
    case LiquidGeometry::Kind::Tank: return "tank";
    case LiquidGeometry::Kind::Channel: return "channel";
    case LiquidGeometry::Kind::Pipe: return "pipe";
  }
  return "?";
}

std::string every_or_none(double interval) {
  return interval > 0 ? "every " + short_number(interval) + " s" : "none";
}

void print_outputs(const LiquidOutput& o) {
  std::printf("outputs: series.csv %s; VTK frames %s%s; summary.json\n", every_or_none(o.series_interval).c_str(),
              every_or_none(o.frame_interval).c_str(),
              o.frame_interval > 0 ? " (velocity, pressure and number density per node)" : "");
  std::string when = o.checkpoint_interval > 0 ? every_or_none(o.checkpoint_interval) : "";
  if (o.checkpoint_at_end) when += (when.empty() ? "" : " and ") + std::string("at the end");
  if (when.empty())
    std::printf("checkpoints: none (output.checkpoint_interval = 0, output.checkpoint_at_end = false)\n");
  else
    std::printf("checkpoints: checkpoints/checkpoint.gfc %s%s; run --resume continues from one\n", when.c_str(),
                o.checkpoint_keep_all ? ", each also kept as checkpoint_<step>.gfc" : "");
}

// An MPS liquid (LiquidSimulation), for the run skeleton (run_model.hpp).
class LiquidModel final : public ScheduledModel {
 public:
  explicit LiquidModel(const LiquidScene& s) : s_(s), sim_(s) {}

  std::string_view kind() const override { return "liquid"; }
  World& world() override { return sim_.world(); }
  Schedule& step() override { return sim_.step(); }
  RunCounts counts() override { return {0, static_cast<std::int64_t>(sim_.nodes().count(kFluid))}; }

  void restore(const CheckpointReader& from) override { restore_liquid_state(from, sim_.world(), s_); }
  std::string opening(std::size_t threads, int) override {
    const std::size_t n_fluid = sim_.nodes().count(kFluid), n_all = sim_.nodes().size();
    char line[256];
    std::snprintf(line, sizeof line, "%zu fluid + %zu wall/dummy nodes, dt = %.3g s (CFL %.3g), %zu threads", n_fluid,
                  n_all - n_fluid, s_.dt, s_.cfl, threads);
    return s_.file.string() + ": " + line;
  }
  void open_summary(nlohmann::json& j) override {
    j["fluid_nodes"] = sim_.nodes().count(kFluid);
    j["nodes"] = sim_.nodes().size();
    j["dt"] = s_.dt;
    j["l0"] = s_.params.k.l0;
    j["cfl_at_load"] = s_.cfl;
    j["diffusion_number"] = s_.diffusion;
  }
  void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) override {
    outputs_ = &observers.emplace<LiquidOutputs>(out, s_, from);
    checkpoints_ = &observers.emplace<CheckpointOutput>(
        CheckpointSettings{out, s_.output.checkpoint_interval, s_.output.checkpoint_keep_all},
        [this](CheckpointWriter& w, World& world) { save_liquid_state(w, world, s_); },
        std::vector<const Checkpointable*>{outputs_});
    if (from) checkpoints_->restore(*from);
    observers.build(sim_.world());
  }

  std::int64_t last_step() const override { return s_.steps(); }
  bool checkpoint_at_end() const override { return s_.output.checkpoint_at_end; }
  // The liquid's first state was observed by the run that wrote the checkpoint.
  bool observe_resumed_start() const override { return false; }
  double rows(const World&) const override { return fluid_nodes_; }

  void close_summary(nlohmann::json& summary, const StageReport& main) override {
    summary["steps_per_second"] = main.wall_seconds > 0 ? static_cast<double>(main.steps) / main.wall_seconds : 0.0;
    const LiquidDiagnostics& d = sim_.diagnostics();
    summary["mean_ppe_iterations"] = d.ppe_solves > 0 ? d.ppe_iterations_total / static_cast<double>(d.ppe_solves) : 0.0;
    summary["frames"] = outputs_->frames();
    summary["final"] = row_json(liquid_series_columns(), sample_liquid(sim_.world(), sim_.scene()));
  }

 private:
  const LiquidScene& s_;
  LiquidSimulation sim_;
  double fluid_nodes_ = static_cast<double>(sim_.nodes().count(kFluid));
  LiquidOutputs* outputs_ = nullptr;
};

}  // namespace

int check_liquid_command(const CliOptions& opt) {
  const LiquidScene s = load_liquid_scene(SceneDoc::load(opt.scene, opt.overrides));
  LiquidSimulation sim(s);
  FluidNodes& f = sim.nodes();
  const LiquidParams& p = s.params;
  std::printf("scene %s: valid\n", s.file.string().c_str());
  std::printf("model: MPS liquid (seed 003: Zhang kernel, Tanaka mixed source gamma = %g), %dD\n", p.gamma, p.k.dim);
  std::printf("geometry: %s; nodes: %zu fluid, %zu wall, %zu dummy\n", geometry_name(s.geometry.kind), f.count(kFluid),
              f.count(kWall), f.count(kDummy));
  std::printf("l0 = %g m, re = %g l0, n0 = %.6g, lambda = %.6g l0^2\n", p.k.l0, p.k.re / p.k.l0, p.k.n0,
              p.k.lambda / (p.k.l0 * p.k.l0));
  std::printf("systems per step (with the systems each waits for):\n%s", sim.step().describe().c_str());
  std::printf("PPE solver: %s, tolerance %g, max %d iterations\n",
              p.solver.kind == PpeSolverKind::ParallelCg ? "Jacobi CG over the compacted couplings (TBB)" : "Eigen ConjugateGradient",
              p.solver.tolerance, p.solver.max_iterations);
  std::printf("dt = %g s: CFL %.3g (velocity scale %.3g m/s, limit %g), diffusion number %.3g (limit %g)%s\n", s.dt,
              s.cfl, s.velocity_scale, s.cfl_limit, s.diffusion, s.diffusion_limit,
              s.allow_unstable_dt && (s.cfl > s.cfl_limit || s.diffusion > s.diffusion_limit) ? " OVERRIDDEN" : "");
  std::printf("steps: %lld (%.4g s simulated)\n", static_cast<long long>(s.steps()), s.duration);
  print_outputs(s.output);
  return 0;
}

int run_liquid_command(const CliOptions& opt) {
  const SceneDoc doc = SceneDoc::load(opt.scene, opt.overrides);
  const LiquidScene s = load_liquid_scene(doc);
  LiquidModel model(s);
  model.scene_json = doc.resolved_json();
  return run_model(model, opt);
}

}  // namespace gf
