// `grainflow run` and `grainflow check` for MPS liquid scenes, with the DEM side's conventions: series.csv
// flushed per row, VTK frames with a .pvd index, summary.json rewritten atomically at start and end, exit code 3
// and status "failed" when a stability detector stops the run, checkpoints in checkpoints/checkpoint.gfc
// (output.checkpoint_interval, at the end unless output.checkpoint_at_end = false) and `--resume` continuing a
// run bit-identically to the same end step.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "engine/atomic_file.hpp"
#include "app/cli.hpp"
#include "engine/run_loop.hpp"
#include "systems/mps/liquid_checkpoint.hpp"
#include "systems/mps/liquid_observables.hpp"
#include "systems/mps/liquid_outputs.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/summary_json.hpp"
#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"

namespace gf {

namespace {

using WallClock = std::chrono::steady_clock;

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

nlohmann::json start_summary(const CliOptions& opt, const LiquidScene& s, LiquidSimulation& sim,
                             const CheckpointReader* ckpt) {
  const FluidNodes& f = sim.nodes();
  const auto& c = sim.world().clock;
  nlohmann::json j;
  summary_opening(j, opt, "liquid", {0, static_cast<std::int64_t>(f.count(kFluid))}, 1, threads_in_use());
  j["fluid_nodes"] = f.count(kFluid);
  j["nodes"] = f.size();
  j["dt"] = s.dt;
  j["l0"] = s.params.k.l0;
  j["cfl_at_load"] = s.cfl;
  j["diffusion_number"] = s.diffusion;
  j["status"] = "running";
  if (ckpt) j["resumed_from"] = resumed_from_json(*ckpt, c);
  return j;
}

// What the stepping loop did.
// The outputs and the checkpoints, observing the state after each step (and the initial state of
// a run that does not resume).
struct LiquidObservers {
  Schedule schedule;
  LiquidOutputs* outputs = nullptr;
  CheckpointOutput* checkpoints = nullptr;
};

void add_observers(LiquidObservers& o, const std::filesystem::path& out, const LiquidScene& s, World& world,
                   const CheckpointReader* from) {
  o.outputs = &o.schedule.emplace<LiquidOutputs>(out, s, from);
  o.checkpoints = &o.schedule.emplace<CheckpointOutput>(
      CheckpointSettings{out, s.output.checkpoint_interval, s.output.checkpoint_keep_all},
      [&s](CheckpointWriter& w, World& wd) { save_liquid_state(w, wd, s); },
      std::vector<const Checkpointable*>{o.outputs});
  if (from) o.checkpoints->restore(*from);
  o.schedule.build(world);
}

void run_and_checkpoint(const CliOptions& opt, const std::filesystem::path& out, const LiquidScene& s,
                        LiquidSimulation& sim, LiquidObservers& obs, bool resumed, RunOutcome& r) {
  const auto run0 = WallClock::now();
  const std::int64_t start = sim.world().clock.step;
  StageOptions so;
  so.steps = std::max<std::int64_t>(0, (opt.steps ? *opt.steps : s.steps()) - start);
  so.observe = &obs.schedule;
  so.observe_start = !resumed;
  so.progress_seconds = opt.quiet ? 0.0 : 2.0;
  const auto n_fluid = static_cast<double>(sim.nodes().count(kFluid));
  so.rows = [n_fluid](const World&) { return n_fluid; };
  guarded(r, opt, out, [&] { return resumed || obs.checkpoints->written() > 0; }, [&] {
    const StageReport rep = run_stage(sim.world(), sim.step(), so);
    if (rep.interrupted) r.status = "interrupted";
    r.wall = seconds_since(run0);
    if (s.output.checkpoint_at_end) r.checkpoint_file = obs.checkpoints->write(sim.world()).string();
  });
  if (r.wall == 0) r.wall = seconds_since(run0);
  r.steps = sim.world().clock.step - start;  // the steps completed, also when one failed
}

void finish_summary(nlohmann::json& summary, LiquidSimulation& sim, const RunOutcome& r, const LiquidOutputs& outputs,
                    const CheckpointOutput& checkpoints) {
  const World& world = sim.world();
  const double n_fluid = static_cast<double>(sim.nodes().count(kFluid));
  const nlohmann::json fin = row_json(liquid_series_columns(), sample_liquid(sim.world(), sim.scene()));
  summary["status"] = r.status;
  if (!r.failure.empty()) summary["failure"] = r.failure;
  summary["steps"] = world.clock.step;
  summary["steps_this_run"] = r.steps;
  summary["simulated_time"] = world.clock.t;
  summary["wall_seconds"] = r.wall;
  summary["steps_per_second"] = r.wall > 0 ? static_cast<double>(r.steps) / r.wall : 0.0;
  summary["particle_steps_per_second"] = r.wall > 0 ? static_cast<double>(r.steps) * n_fluid / r.wall : 0.0;
  const LiquidDiagnostics& d = sim.diagnostics();
  summary["mean_ppe_iterations"] = d.ppe_solves > 0 ? d.ppe_iterations_total / static_cast<double>(d.ppe_solves) : 0.0;
  summary["frames"] = outputs.frames();
  summary["checkpoints_written"] = checkpoints.written();
  if (!r.checkpoint_file.empty()) summary["checkpoint"] = r.checkpoint_file;
  summary["final"] = fin;
  summary_counts_at_end(summary, {0, static_cast<std::int64_t>(n_fluid)});
  summary["time_per_system"] = timings_json({&sim.step()});
}

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
  const auto wall0 = WallClock::now();
  const LiquidScene s = load_liquid_scene(SceneDoc::load(opt.scene, opt.overrides));
  const std::filesystem::path out = opt.out_dir();
  ensure_directory(out);
  LiquidSimulation sim(s);
  World& world = sim.world();
  std::optional<CheckpointReader> ckpt;
  if (opt.resume) {
    ckpt.emplace(*opt.resume);
    restore_liquid_state(*ckpt, world, s);
  }
  const CheckpointReader* from = ckpt ? &*ckpt : nullptr;
  const std::size_t n_fluid = sim.nodes().count(kFluid), n_all = sim.nodes().size();
  std::fprintf(stderr, "grainflow: %s: %zu fluid + %zu wall/dummy nodes, dt = %.3g s (CFL %.3g), %zu threads -> %s\n",
               s.file.string().c_str(), n_fluid, n_all - n_fluid, s.dt, s.cfl, threads_in_use(), out.string().c_str());
  if (ckpt)
    say_resuming(*ckpt, world.clock);
  nlohmann::json summary = start_summary(opt, s, sim, from);
  write_summary_json(out / "summary.json", summary);

  LiquidObservers obs;
  add_observers(obs, out, s, world, from);
  RunOutcome r;
  run_and_checkpoint(opt, out, s, sim, obs, ckpt.has_value(), r);
  finish_summary(summary, sim, r, *obs.outputs, *obs.checkpoints);
  summary["total_wall_seconds"] = seconds_since(wall0);
  try {
    write_summary_json(out / "summary.json", summary);
  } catch (const WriteError& e) {
    // The earlier summary.json (status "running") stays as it was.
    r.fail_also(e.what());
  }
  char rate[64];
  std::snprintf(rate, sizeof rate, ": %.3g particle-steps/s",
                r.wall > 0 ? static_cast<double>(r.steps) * static_cast<double>(n_fluid) / r.wall : 0.0);
  say_done(r, world.clock.t, rate);
  return r.rc;
}

}  // namespace gf
