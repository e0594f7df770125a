// `grainflow run` and `grainflow check` for scenes of a liquid with grains in it (coupled_scene.hpp):
// series.csv (output.series_interval) with the liquid's and the grains' columns, VTK frames of both
// (output.frame_interval: liquid/frames.pvd, grains/frames.pvd), final_state.csv, summary.json rewritten
// atomically at start and end, exit code 3 and status "failed" when a stability detector stops the run.
// Checkpoints (output.checkpoint_interval, and at the end unless output.checkpoint_at_end = false:
// coupled_checkpoint.hpp) and `--resume` continuing series and frames bit for bit, as a liquid run's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/run_model.hpp"
#include "app/run_outcome.hpp"
#include "systems/coupling/coupled_observables.hpp"
#include "systems/coupling/coupled_step.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_outputs.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/wall_loads_csv.hpp"
#include "systems/setup/coupled_checkpoint.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "systems/setup/dem_output_settings.hpp"
#include "systems/setup/final_state.hpp"

namespace gf {

namespace {

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

// series.csv: a row every `every` liquid steps, from step 0; a resumed run continues the file from the
// rows its checkpoint counted. Beside it, when the grains have walls, walls.csv: each wall's mean load
// over the DEM sub-steps since the previous row (wall_loads_csv.hpp), its running sums checkpointed.
class CoupledSeries : public SystemBase<CoupledSeries>, public Checkpointable {
 public:
  using Reads = gf::Reads<FluidNodes, Position, Velocity, Walls, MeshWallLoads>;
  using Writes = gf::Writes<SeriesRow>;  // before the checkpoint, which counts the rows
  CoupledSeries(const std::filesystem::path& file, const CoupledScene& s, std::int64_t every, const CheckpointReader* from)
      : csv_(from ? SeriesCsv::resume(file, coupled_series_columns(), from->value<std::uint64_t>("coupled_series.rows"))
                  : SeriesCsv(file, coupled_series_columns())),
        s_(s), every_(every), rows_(from ? from->value<std::uint64_t>("coupled_series.rows") : 0) {
    const SeriesSettings walls = scene_series_settings(s.dem, file.parent_path());
    if (walls.wall_names.empty()) return;
    // A resumed run keeps the rows through the checkpoint's time (its row there, if any, came before it).
    const double resume_time = from ? from->value<double>("clock.t") : std::numeric_limits<double>::quiet_NaN();
    walls_csv_ = std::make_unique<WallLoadsCsv>(file.parent_path() / "walls.csv", walls.wall_names,
                                                walls.analytic_walls, resume_time);
    if (from) walls_csv_->restore(*from);
  }
  std::string_view name() const override { return "series_output"; }
  void run(World& w, const StepContext&) override {
    if (w.clock.step % every_ != 0) return;
    csv_.append(sample_coupled(w, s_.liquid));
    ++rows_;
    if (walls_csv_) walls_csv_->write(w.clock.t, &w.resources.get<Walls>().loads, w.resources.find<MeshWallLoads>());
  }
  void save(CheckpointWriter& out) const override {
    out.value("coupled_series.rows", rows_);
    if (walls_csv_) walls_csv_->save(out);
  }
  void restore(const CheckpointReader& in) override { rows_ = in.value<std::uint64_t>("coupled_series.rows"); }

 private:
  SeriesCsv csv_;
  const CoupledScene& s_;
  std::int64_t every_;
  std::uint64_t rows_ = 0;
  std::unique_ptr<WallLoadsCsv> walls_csv_;
};

// An MPS liquid with DEM grains (CoupledSimulation), for the run skeleton (run_model.hpp).
class CoupledModel final : public ScheduledModel {
 public:
  explicit CoupledModel(CoupledScene s) : sim_(std::move(s)) {}

  std::string_view kind() const override { return "coupled"; }
  World& world() override { return sim_.world(); }
  Schedule& step() override { return sim_.step(); }
  RunCounts counts() override { return {grains(), fluid_nodes()}; }

  void restore(const CheckpointReader& from) override { sim_.resume(from); }
  std::string opening(std::size_t, int) override {
    const CoupledScene& s = sim_.scene();
    char line[256];
    std::snprintf(line, sizeof line, "liquid and %lld grains, dt = %.3g s with %d DEM sub-steps",
                  static_cast<long long>(grains()), s.liquid.dt, s.coupling.substeps);
    return s.file.string() + ": " + line;
  }
  void open_summary(nlohmann::json& j) override;
  // No settling: the first state's forces, then the main stage.
  StageReport settle(double) override {
    sim_.prime();
    return {};
  }
  void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) override;

  std::int64_t last_step() const override { return scene().steps(); }
  bool checkpoint_at_end() const override { return scene().liquid.output.checkpoint_at_end; }
  bool observe_resumed_start() const override { return false; }
  // A step advances every liquid node and every grain once (the grains in k sub-steps).
  double rows(const World& w) const override {
    return static_cast<double>(w.grains.n_owned) + fluid_nodes_at_start_;
  }

  void close_summary(nlohmann::json& summary, const StageReport&) override {
    summary["final"] = row_json(coupled_series_columns(), sample_coupled(sim_.world(), scene().liquid));
    summary["time_per_dem_system"] = timings_json({&sim_.dem_substeps().inner()});
  }
  void write_final_files(const std::filesystem::path& out) override {
    write_final_state(out / "final_state.csv", sim_.world().grains);
  }

 private:
  const CoupledScene& scene() const { return *scene_; }
  std::int64_t grains() { return static_cast<std::int64_t>(sim_.world().grains.n_owned); }
  std::int64_t fluid_nodes() { return static_cast<std::int64_t>(sim_.world().tables.get<FluidNodes>().count(kFluid)); }

  CoupledSimulation sim_;
  const CoupledScene* scene_ = &sim_.scene();
  double fluid_nodes_at_start_ = static_cast<double>(fluid_nodes());  // the liquid keeps its nodes
  LiquidScene frame_scene_;  // the liquid's outputs: frames only (the coupled series takes its series' place)
};

void CoupledModel::open_summary(nlohmann::json& j) {
  const CoupledScene& s = scene();
  j["fluid_nodes"] = fluid_nodes();
  j["grains"] = grains();
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
}

// The outputs and the checkpoints, observing the state after each step (and the initial state of a run
// that does not resume).
void CoupledModel::observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) {
  const CoupledScene& s = scene();
  frame_scene_ = s.liquid;
  frame_scene_.output.series_interval = 0;
  std::vector<const Checkpointable*> parts;
  if (s.liquid.output.frame_interval > 0) {
    if (from && !from->has("grain_frames.next"))
      from->fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    parts.push_back(&observers.emplace<LiquidOutputs>(out / "liquid", frame_scene_, from));
    auto& grains = observers.emplace<FrameOutput>(out / "grains", s.liquid.output.frame_interval, FrameFields{}, "grain_frames");
    if (from) grains.restore(*from);
    parts.push_back(&grains);
  }
  const std::int64_t every = std::max<std::int64_t>(1, std::llround(s.liquid.output.series_interval / s.liquid.dt));
  if (s.liquid.output.series_interval > 0)
    parts.push_back(&observers.emplace<CoupledSeries>(out / "series.csv", s, every, from));
  checkpoints_ = &observers.emplace<CheckpointOutput>(
      CheckpointSettings{out, s.liquid.output.checkpoint_interval, s.liquid.output.checkpoint_keep_all},
      [&s](CheckpointWriter& w, World& wd) { save_coupled_state(w, wd, s); }, parts);
  if (from) checkpoints_->restore(*from);
  observers.build(sim_.world());
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
  const bool walls = o.series_interval > 0 && !(s.dem.walls.empty() && s.dem.mesh_walls.list.empty());
  std::printf("outputs: series.csv %s%s; VTK frames %s; summary.json; final_state.csv (the grains); checkpoints "
              "(checkpoints/checkpoint.gfc) %s; run --resume continues from one\n",
              o.series_interval > 0 ? ("every " + short_number(o.series_interval) + " s").c_str() : "none",
              walls ? ", and walls.csv at its rows" : "",
              o.frame_interval > 0 ? ("every " + short_number(o.frame_interval) + " s (liquid/frames.pvd, grains/frames.pvd)").c_str() : "none",
              o.checkpoint_interval > 0 ? ("every " + short_number(o.checkpoint_interval) + " s and " + at_end).c_str() : at_end.c_str());
  return 0;
}

int run_coupled_command(const CliOptions& opt) {
  const SceneDoc doc = SceneDoc::load(opt.scene, opt.overrides);
  CoupledModel model(load_coupled_scene(doc));
  model.scene_json = doc.resolved_json();
  return run_model(model, opt);
}

}  // namespace gf
