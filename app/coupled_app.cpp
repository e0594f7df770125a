// `grainflow run` and `grainflow check` for scenes of a liquid with grains in it (coupled_scene.hpp):
// series.csv (output.series_interval) with the liquid's and the grains' columns, VTK frames of both
// (output.frame_interval: liquid/frames.pvd, grains/frames.pvd), final_state.csv, summary.json rewritten
// atomically at start and end, exit code 3 and status "failed" when a stability detector stops the run.
// Checkpoints (output.checkpoint_interval, and at the end unless output.checkpoint_at_end = false:
// coupled_checkpoint.hpp) and `--resume` continuing series and frames bit for bit, as a liquid run's.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/atomic_file.hpp"
#include "app/cli.hpp"
#include "engine/run_loop.hpp"
#include "systems/coupling/coupled_observables.hpp"
#include "systems/coupling/coupled_step.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_outputs.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/summary_json.hpp"
#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"
#include "systems/setup/coupled_checkpoint.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "systems/setup/final_state.hpp"

namespace gf {

namespace {

using WallClock = std::chrono::steady_clock;

void print_liquid_part(const CoupledScene& s, World& w) {
  const LiquidScene& l = s.liquid;
  const FluidNodes& f = w.tables.get<FluidNodes>();
  std::printf("liquid: MPS, %dD, l0 = %g m, re = %g l0, density %g kg/m^3, viscosity %g m^2/s; nodes: %zu fluid, %zu wall, %zu dummy\n",
              l.params.k.dim, l.params.k.l0, l.params.k.re / l.params.k.l0, l.params.rho, l.params.nu, f.count(kFluid),
              f.count(kWall), f.count(kDummy));
  std::printf("liquid step dt = %g s: CFL %.3g (velocity scale %.3g m/s, limit %g), diffusion number %.3g (limit %g)\n",
              l.dt, l.cfl, l.velocity_scale, l.cfl_limit, l.diffusion, l.diffusion_limit);
}

void print_grain_part(const CoupledScene& s, World& w) {
  const DemScene& d = s.dem;
  std::printf("grains: %zu in %zu species, contact law %s; walls: %zu and %zu of mesh; fills: %zu\n", w.grains.n_owned,
              d.species.size(), d.law.c_str(), d.walls.size(), d.mesh_walls.list.size(), d.fills.size());
  std::printf("DEM sub-step dt/k = %.4g s = %.3f of the contact law's smallest time-step term %.4g s (%s; limit %.3f)\n",
              d.dt, d.dt / d.critical.period, d.critical.period, d.critical.term.c_str(), d.dt_safety);
}

void print_coupling(const CoupledScene& s) {
  const CouplingSpec& c = s.coupling;
  std::printf("coupling: k = %d DEM sub-steps per liquid step (%s); smoothing radius h = %g m (%.3g l0); drag %s; "
              "buoyancy -V_p rho_l g (Archimedes); min liquid fraction %g\n",
              c.substeps, c.substeps_computed ? "computed: the fewest within the DEM step limit" : "coupling.substeps",
              c.smoothing_radius, c.smoothing_radius / s.liquid.params.k.l0, drag_model_name(c.drag), c.min_liquid_fraction);
  std::printf("shares: %s\n", c.fluid_nodes_only ? "over the fluid nodes within h only (share_with = \"fluid_nodes\")"
                                                 : "over every node within h, wall and dummy nodes included");
  if (c.fixed_grains)
    std::printf("grains: held fixed (coupling.fixed_grains): the liquid's force and its reaction only, no contacts\n");
  if (c.modified_pressure)
    std::printf("liquid pressure: modified (the hydrostatic part removed, no gravity in the liquid's step: a closed, "
                "filled box)\n");
  std::printf("liquid model: %s; the reaction reaches the nodes as a momentum change\n",
              c.averaged ? "locally averaged (coupling.averaged: the nodes' number-density target and free-surface test are eps n0)"
                         : "not locally averaged (coupling.averaged = false: the liquid fills the grains' volume)");
}

nlohmann::json start_summary(const CliOptions& opt, const CoupledScene& s, CoupledSimulation& sim) {
  nlohmann::json j;
  summary_opening(j, opt, "coupled",
                  {static_cast<std::int64_t>(sim.world().grains.n_owned),
                   static_cast<std::int64_t>(sim.world().tables.get<FluidNodes>().count(kFluid))},
                  1, threads_in_use());
  j["fluid_nodes"] = sim.world().tables.get<FluidNodes>().count(kFluid);
  j["grains"] = sim.world().grains.n_owned;
  j["dt"] = s.liquid.dt;
  j["dem_dt"] = s.dem.dt;
  j["substeps"] = s.coupling.substeps;
  j["substeps_computed"] = s.coupling.substeps_computed;
  j["l0"] = s.liquid.params.k.l0;
  j["smoothing_radius"] = s.coupling.smoothing_radius;
  j["drag"] = drag_model_name(s.coupling.drag);
  j["buoyancy"] = "archimedes";
  j["modified_pressure"] = s.coupling.modified_pressure;
  j["fixed_grains"] = s.coupling.fixed_grains;
  j["share_with"] = s.coupling.fluid_nodes_only ? "fluid_nodes" : "all_nodes";
  j["averaged"] = s.coupling.averaged;
  j["status"] = "running";
  return j;
}

// series.csv: a row every `every` liquid steps, from step 0; a resumed run continues the file from the
// rows its checkpoint counted.
class CoupledSeries : public SystemBase<CoupledSeries>, public Checkpointable {
 public:
  using Reads = gf::Reads<FluidNodes, Position, Velocity>;
  using Writes = gf::Writes<SeriesRow>;  // before the checkpoint, which counts the rows
  CoupledSeries(const std::filesystem::path& file, const CoupledScene& s, std::int64_t every, const CheckpointReader* from)
      : csv_(from ? SeriesCsv::resume(file, coupled_series_columns(), from->value<std::uint64_t>("coupled_series.rows"))
                  : SeriesCsv(file, coupled_series_columns())),
        s_(s), every_(every), rows_(from ? from->value<std::uint64_t>("coupled_series.rows") : 0) {}
  std::string_view name() const override { return "series_output"; }
  void run(World& w, const StepContext&) override {
    if (w.clock.step % every_ != 0) return;
    csv_.append(sample_coupled(w, s_.liquid));
    ++rows_;
  }
  void save(CheckpointWriter& out) const override { out.value("coupled_series.rows", rows_); }
  void restore(const CheckpointReader& in) override { rows_ = in.value<std::uint64_t>("coupled_series.rows"); }

 private:
  SeriesCsv csv_;
  const CoupledScene& s_;
  std::int64_t every_;
  std::uint64_t rows_ = 0;
};

// The outputs and the checkpoints, observing the state after each step (and the initial state of a run
// that does not resume).
struct CoupledObservers {
  Schedule schedule;
  CheckpointOutput* checkpoints = nullptr;
  LiquidScene frame_scene;  // the liquid's outputs: frames only (the coupled series takes its series' place)
};

void add_observers(CoupledObservers& o, const std::filesystem::path& out, const CoupledScene& s, World& world,
                   const CheckpointReader* from) {
  o.frame_scene = s.liquid;
  o.frame_scene.output.series_interval = 0;
  std::vector<const Checkpointable*> parts;
  if (s.liquid.output.frame_interval > 0) {
    if (from && !from->has("grain_frames.next"))
      from->fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    parts.push_back(&o.schedule.emplace<LiquidOutputs>(out / "liquid", o.frame_scene, from));
    auto& grains = o.schedule.emplace<FrameOutput>(out / "grains", s.liquid.output.frame_interval, FrameFields{}, "grain_frames");
    if (from) grains.restore(*from);
    parts.push_back(&grains);
  }
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(s.liquid.output.series_interval / s.liquid.dt));
  if (s.liquid.output.series_interval > 0) parts.push_back(&o.schedule.emplace<CoupledSeries>(out / "series.csv", s, every, from));
  o.checkpoints = &o.schedule.emplace<CheckpointOutput>(
      CheckpointSettings{out, s.liquid.output.checkpoint_interval, s.liquid.output.checkpoint_keep_all},
      [&s](CheckpointWriter& w, World& wd) { save_coupled_state(w, wd, s); }, parts);
  if (from) o.checkpoints->restore(*from);
  o.schedule.build(world);
}

void step_to(std::int64_t end, CoupledSimulation& sim, Schedule& observe, bool resumed, bool quiet, RunOutcome& r) {
  World& w = sim.world();
  if (!resumed) sim.prime();
  const std::int64_t start = w.clock.step;
  StageOptions so;
  so.steps = std::max<std::int64_t>(0, end - start);
  so.observe = &observe;
  so.observe_start = !resumed;
  so.progress_seconds = quiet ? 0.0 : 2.0;
  try {
    if (run_stage(w, sim.step(), so).interrupted) r.status = "interrupted";
  } catch (...) {
    r.steps = w.clock.step - start;
    throw;
  }
  r.steps = w.clock.step - start;
}

}  // namespace

int check_coupled_command(const CliOptions& opt) {
  CoupledSimulation sim(load_coupled_scene(SceneDoc::load(opt.scene, opt.overrides)));
  sim.prime();
  const CoupledScene& s = sim.scene();
  std::printf("scene %s: valid\n", s.file.string().c_str());
  std::printf("model: MPS liquid with DEM grains (seed 003), one step: the liquid's, with k DEM sub-steps inside\n");
  print_liquid_part(s, sim.world());
  print_grain_part(s, sim.world());
  print_coupling(s);
  std::printf("systems per step (with the systems each waits for):\n%s", sim.step().describe().c_str());
  std::printf("DEM sub-step systems:\n%s", sim.dem_substeps().inner().describe().c_str());
  std::printf("steps: %lld liquid steps of %g s (%.4g s simulated), %lld DEM sub-steps\n",
              static_cast<long long>(s.steps()), s.liquid.dt, s.liquid.duration,
              static_cast<long long>(s.steps()) * s.coupling.substeps);
  const LiquidOutput& o = s.liquid.output;
  const std::string at_end = o.checkpoint_at_end ? "at the end" : "not at the end";
  std::printf("outputs: series.csv %s; VTK frames %s; summary.json; final_state.csv (the grains); checkpoints "
              "(checkpoints/checkpoint.gfc) %s; run --resume continues from one\n",
              o.series_interval > 0 ? ("every " + short_number(o.series_interval) + " s").c_str() : "none",
              o.frame_interval > 0 ? ("every " + short_number(o.frame_interval) + " s (liquid/frames.pvd, grains/frames.pvd)").c_str() : "none",
              o.checkpoint_interval > 0 ? ("every " + short_number(o.checkpoint_interval) + " s and " + at_end).c_str() : at_end.c_str());
  return 0;
}

int run_coupled_command(const CliOptions& opt) {
  const auto wall0 = WallClock::now();
  CoupledSimulation sim(load_coupled_scene(SceneDoc::load(opt.scene, opt.overrides)));
  const CoupledScene& s = sim.scene();
  std::optional<CheckpointReader> ckpt;
  if (opt.resume) {
    ckpt.emplace(*opt.resume);
    sim.resume(*ckpt);
  }
  const CheckpointReader* from = ckpt ? &*ckpt : nullptr;
  const std::filesystem::path out = opt.out_dir();
  ensure_directory(out);
  std::fprintf(stderr, "grainflow: %s: liquid and %zu grains, dt = %.3g s with %d DEM sub-steps -> %s\n",
               s.file.string().c_str(), sim.world().grains.n_owned, s.liquid.dt, s.coupling.substeps, out.string().c_str());
  if (ckpt) say_resuming(*ckpt, sim.world().clock);
  nlohmann::json summary = start_summary(opt, s, sim);
  if (ckpt) summary["resumed_from"] = resumed_from_json(*ckpt, sim.world().clock);
  write_summary_json(out / "summary.json", summary);
  CoupledObservers obs;
  add_observers(obs, out, s, sim.world(), from);
  RunOutcome r;
  const auto run0 = WallClock::now();
  const auto have_checkpoint = [&] { return ckpt.has_value() || obs.checkpoints->written() > 0; };
  guarded(r, opt, out, have_checkpoint, [&] {
    step_to(opt.steps ? *opt.steps : s.steps(), sim, obs.schedule, ckpt.has_value(), opt.quiet, r);
    if (s.liquid.output.checkpoint_at_end) r.checkpoint_file = obs.checkpoints->write(sim.world()).string();
  });
  r.wall = seconds_since(run0);
  const nlohmann::json fin = row_json(coupled_series_columns(), sample_coupled(sim.world(), s.liquid));
  summary["status"] = r.status;
  if (!r.failure.empty()) summary["failure"] = r.failure;
  summary["steps"] = sim.world().clock.step;
  summary["steps_this_run"] = r.steps;
  summary["simulated_time"] = sim.world().clock.t;
  summary["wall_seconds"] = r.wall;
  summary["total_wall_seconds"] = seconds_since(wall0);
  summary["checkpoints_written"] = obs.checkpoints->written();
  if (!r.checkpoint_file.empty()) summary["checkpoint"] = r.checkpoint_file;
  summary["final"] = fin;
  summary_counts_at_end(summary, {static_cast<std::int64_t>(sim.world().grains.n_owned),
                                  static_cast<std::int64_t>(sim.world().tables.get<FluidNodes>().count(kFluid))});
  summary["time_per_system"] = timings_json({&sim.step()});
  summary["time_per_dem_system"] = timings_json({&sim.dem_substeps().inner()});
  try {
    write_final_state(out / "final_state.csv", sim.world().grains, s.dem);
    write_summary_json(out / "summary.json", summary);
  } catch (const WriteError& e) {
    // The earlier summary.json (status "running") stays as it was.
    if (r.failure.empty()) r.fail(e.what() + write_failure_fix(opt, out, have_checkpoint()));
    else r.fail_also(e.what());
  }
  say_done(r, sim.world().clock.t, "");
  return r.rc;
}

}  // namespace gf
