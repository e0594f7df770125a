// `grainflow run` and `grainflow check` for DEM scenes.
#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include <tbb/global_control.h>

#include "engine/atomic_file.hpp"
#include "app/cli.hpp"
#include "engine/run_loop.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/contact/laws.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/setup/dem_output_settings.hpp"
#include "systems/output/layer_output.hpp"
#include "systems/output/residence_csv.hpp"
#include "systems/output/summary_json.hpp"
#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"
#include "app/dem_body_app.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "systems/setup/final_state.hpp"
#include "systems/setup/flow_scene.hpp"

namespace gf {

namespace {

nlohmann::json flow_json(const FlowState& f, const Grains& g, const ResidenceOutput* residence) {
  double kg = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) kg += g.mass.m[i];
  nlohmann::json j = {{"grains", g.n_owned},          {"holdup_mass", kg},
                      {"fed_grains", f.fed_grains()}, {"fed_mass", f.fed_mass()},
                      {"discharged", f.discharged()}, {"discharged_mass", f.discharged_mass()},
                      {"feed_backlog", f.backlog()}};
  if (residence) j["residence_rows"] = residence->rows();
  return j;
}

void print_flow(const DemScene& s) {
  for (std::size_t k = 0; k < s.flow.feeds.size(); ++k) {
    const FeedSpec& f = s.flow.feeds[k];
    std::string mix;
    for (const FeedSpecies& sp : f.species)
      mix += (mix.empty() ? "" : ", ") + s.species[sp.type].name + " " + short_number(sp.fraction);
    std::printf("feed[%zu]: %.4g kg/s (%s by mass) every %.4g s from %.4g s%s\n", k, f.mass_rate, mix.c_str(),
                f.interval, f.start, std::isfinite(f.stop) ? (" to " + short_number(f.stop) + " s").c_str() : "");
  }
  for (std::size_t k = 0; k < s.flow.outlets.size(); ++k)
    std::printf("outlet[%zu]: grains leave when their centre is inside its region, checked every %.4g s; "
                "residence.csv records each\n", k, s.flow.outlets[k].interval);
  if (!s.flow.feeds.empty())
    std::printf("feeds insert at most %zu grains over the run (the memory allows %zu in the table)\n",
                max_fed_grains(s), memory_grain_limit(s));
}

}  // namespace

int check_dem_command(const CliOptions& opt) {
  const SceneDoc doc = SceneDoc::load(opt.scene, opt.overrides);
  const DemScene s = load_dem_scene(doc);
  if (s.bodies) return check_body_command(opt, s);  // composite grains: their own outputs
  // The fills are built and the initial forces computed as `run` does, so check refuses what run
  // would (a state file's bad row, a region through a wall, an empty world, more grains than the
  // memory holds, grains that start overlapping past the limit).
  DemSimulation sim(s);
  sim.prime();
  const Schedule& step = sim.step();
  const std::size_t n = sim.grains().n_owned;
  std::printf("scene %s: valid\n", s.file.string().c_str());
  with_law(s.law, [&]<class Law>() {
    const HistoryLayout h = Law::history();
    std::string fields;
    for (std::string_view f : h.fields) fields += (fields.empty() ? "" : ", ") + std::string(f);
    std::printf("model: dry soft-sphere DEM; contact law %s: %s\n", s.law.c_str(), std::string(Law::title).c_str());
    if (h.fields.empty())
      std::printf("contact history: none (the law keeps no state per contact)\n");
    else
      std::printf("contact history: %s (%s; %zu doubles per contact)\n", std::string(h.component).c_str(),
                  fields.c_str(), h.fields.size());
  });
  if (s.contacts->reach() > 0.0)
    std::printf("reach beyond touching: %.4g m (pairs closer than r_i + r_j + reach interact; the neighbour search "
                "looks reach + skin past touching)\n",
                s.contacts->reach());
  std::printf("grains: %zu in %zu species; walls: %zu and %zu of mesh; fills: %zu; feeds: %zu; outlets: %zu\n", n,
              s.species.size(), s.walls.size(), s.mesh_walls.list.size(), s.fills.size(), s.flow.feeds.size(),
              s.flow.outlets.size());
  std::size_t rotating = 0;
  for (const SpeciesSpec& sp : s.species) rotating += sp.rotates;
  if (rotating == s.species.size())
    std::printf("rotation: every species rotates (angular velocity and torques integrated)\n");
  else if (rotating == 0)
    std::printf("rotation: no species rotates: translation only, the grains have no spin columns\n");
  else
    std::printf("rotation: %zu of %zu species rotate (the others have zero inverse inertia)\n", rotating,
                s.species.size());
  std::printf("systems per step (with the systems each waits for):\n%s", step.describe().c_str());
  std::printf("observers: series_output, frame_output, picture_output%s\n",
              s.flow.outlets.empty() ? "" : ", residence_output");
  if (s.layers)
    std::printf("layers: %zu transverse layers %.4g m thick, cells of %.4g m (at least %d grains), every %.4g s -> "
                "layers.csv\n",
                s.layers->distances.size(), s.layers->thickness, s.layers->cell, s.layers->min_grains,
                s.layers->interval);
  print_flow(s);
  std::printf("critical step: smallest time-step term %.4g s (%s); dt = %.4g s = %.3f of it (limit %.3f)%s\n",
              s.critical.period, s.critical.term.c_str(), s.dt, s.dt / s.critical.period, s.dt_safety,
              s.allow_unstable_dt && s.dt > s.dt_safety * s.critical.period ? " OVERRIDDEN" : "");
  std::printf("steps: %lld settling + %lld main (%.4g s simulated)\n", static_cast<long long>(s.settle_steps()),
              static_cast<long long>(s.main_steps()), s.duration);
  // A continuous scene grows as its feeds insert grains: the estimate counts the most they can insert.
  const std::size_t n_most = s.flow.feeds.empty() ? n : n + std::min(max_fed_grains(s), memory_grain_limit(s));
  const double mb = static_cast<double>(estimate_memory_bytes(s, n_most)) / 1048576.0;
  std::printf("memory estimate, simulation arrays: %.1f MiB (%.0f bytes per grain; the process adds its code and buffers)\n", mb, n_most ? mb * 1048576.0 / n_most : 0.0);
  return 0;
}

namespace {

// The observers of a grain run (series, frames, pictures, residence and layer files, checkpoints), each
// restored from the checkpoint a run resumes.
struct DemObservers {
  Schedule schedule;
  SeriesOutput* series = nullptr;
  FrameOutput* frames = nullptr;
  PictureOutput* pictures = nullptr;
  ResidenceOutput* residence = nullptr;
  LayerOutput* layers = nullptr;
  CheckpointOutput* checkpoints = nullptr;
};

void restore_observers(DemObservers& o, const CheckpointReader& ckpt) {
  o.series->restore(ckpt);
  if (o.frames) {
    if (!ckpt.has("frame_output.next"))
      ckpt.fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    o.frames->restore(ckpt);
  }
  if (o.pictures) {
    if (!ckpt.has("picture_output.next_angle"))
      ckpt.fail("the run that wrote it drew no pictures",
                "resume without output.picture_angles and output.picture_interval, as that run had");
    o.pictures->restore(ckpt);
  }
  if (o.residence) o.residence->restore(ckpt);
  if (o.layers) o.layers->restore(ckpt);
  o.checkpoints->restore(ckpt);
}

void add_observers(DemObservers& o, const DemScene& s, const std::filesystem::path& out, World& world,
                   const CheckpointReader* ckpt) {
  world.resources.emplace<SeriesRow>();
  SeriesSettings ss = scene_series_settings(s, out);
  if (ckpt) {
    ss.resume_rows = ckpt->value<std::uint64_t>("series_output.rows");
    ss.resume_time = world.clock.t;
  }
  o.series = &o.schedule.emplace<SeriesOutput>(ss);
  if (s.output.frame_interval > 0) o.frames = &o.schedule.emplace<FrameOutput>(out, s.output.frame_interval, s.output.fields);
  if (scene_draws_pictures(s)) o.pictures = &o.schedule.emplace<PictureOutput>(scene_picture_settings(s, out));
  if (!s.flow.outlets.empty()) {
    std::optional<std::size_t> keep;
    if (ckpt) keep = ckpt->value<std::uint64_t>("residence_output.rows");
    o.residence = &o.schedule.emplace<ResidenceOutput>(out / "residence.csv", keep);
  }
  if (s.layers) {
    std::optional<std::size_t> keep;
    if (ckpt) keep = ckpt->value<std::uint64_t>("layer_output.rows");
    o.layers = &o.schedule.emplace<LayerOutput>(out / "layers.csv", *s.layers, keep);
  }
  std::vector<const Checkpointable*> parts{o.series};
  if (o.layers) parts.push_back(o.layers);
  if (o.frames) parts.push_back(o.frames);
  if (o.pictures) parts.push_back(o.pictures);
  if (o.residence) parts.push_back(o.residence);
  o.checkpoints = &o.schedule.emplace<CheckpointOutput>(
      CheckpointSettings{out, s.output.checkpoint_interval, s.output.checkpoint_keep_all},
      [&s](CheckpointWriter& w, World& wd) { save_dem_state(w, wd, s); }, parts);
  o.schedule.build(world);
  if (ckpt) restore_observers(o, *ckpt);
}

// The main stage with its observers, then the checkpoint at the end and the outputs' last writes; a
// failure ends the stage and is recorded in `r`, the files written before kept. Returns the stage's report.
StageReport step_main_stage(const CliOptions& opt, const DemScene& s, DemSimulation& sim, DemObservers& o,
                            const std::filesystem::path& out, const CheckpointReader* ckpt, RunOutcome& r) {
  World& world = sim.world();
  StageOptions so;
  so.progress_seconds = opt.quiet ? 0.0 : 2.0;
  so.label = "run";
  // --steps and the scene's duration count the whole main stage, so a resumed run ends where the
  // uninterrupted one would.
  const std::int64_t total_steps = opt.steps ? *opt.steps : s.main_steps();
  so.steps = std::max<std::int64_t>(0, total_steps - world.clock.step);
  so.observe = &o.schedule;
  const auto run0 = std::chrono::steady_clock::now();
  const auto have_checkpoint = [&] { return ckpt != nullptr || o.checkpoints->written() > 0; };
  StageReport main;
  guarded(r, opt, out, have_checkpoint, [&] {
    main = run_stage(world, sim.step(), so);
    if (main.interrupted) r.status = "interrupted";
  });
  if (r.failed()) {  // a stage that threw: the steps it took, and its wall time
    main.steps = world.clock.step - (ckpt ? ckpt->value<std::int64_t>("clock.step") : 0);
    main.wall_seconds = seconds_since(run0);
  }
  if (s.output.checkpoint_at_end)
    guarded(r, opt, out, have_checkpoint, [&] { r.checkpoint_file = o.checkpoints->write(world).string(); });
  guarded(r, opt, out, have_checkpoint, [&] {
    o.series->finish(world);
    if (o.frames) o.frames->finish(world);
  });
  r.steps = main.steps;
  r.wall = main.wall_seconds;
  return main;
}

void summarise_run(nlohmann::json& summary, const RunOutcome& r, const StageReport& main, const StageReport& settle,
                   const DemObservers& o, DemSimulation& sim, std::size_t n, double total_wall) {
  World& world = sim.world();
  // A stage that threw reports its steps but not the grains stepped: those of the start, then.
  const double stepped = main.particle_steps > 0 ? main.particle_steps : static_cast<double>(main.steps) * n;
  summary["status"] = r.status;
  if (!r.failure.empty()) summary["failure"] = r.failure;
  summary["settle"] = {{"steps", settle.steps}, {"wall_seconds", settle.wall_seconds}};
  summary["steps"] = world.clock.step;
  summary["steps_this_run"] = main.steps;
  summary["checkpoints_written"] = o.checkpoints->written();
  if (!r.checkpoint_file.empty()) summary["checkpoint"] = r.checkpoint_file;
  summary["simulated_time"] = world.clock.t;
  summary["wall_seconds"] = main.wall_seconds;
  summary["total_wall_seconds"] = total_wall;
  summary["particle_steps_per_second"] = main.wall_seconds > 0 ? stepped / main.wall_seconds : 0.0;
  summary["neighbor_rebuilds"] = world.resources.get<BroadphaseState>().rebuilds;
  // Checks where some grain had moved past skin/2 but no pair missing from the list touched.
  summary["neighbor_list_kept"] = world.resources.get<BroadphaseState>().cover.kept;
  summary["frames"] = o.frames ? o.frames->frames() : 0;
  summary["pictures"] = o.pictures ? o.pictures->pictures() : 0;
  summary["final"] = final_row_json(world.resources.get<SeriesRow>());
  if (const FlowState* f = world.resources.find<FlowState>()) summary["flow"] = flow_json(*f, world.grains, o.residence);
  summary_counts_at_end(summary, {static_cast<std::int64_t>(world.grains.n_owned), 0});
  summary["time_per_system"] = timings_json({&sim.step(), &o.schedule});
}

nlohmann::json opening_summary(const CliOptions& opt, const DemScene& s, const World& world, std::size_t n,
                               const CheckpointReader* ckpt) {
  nlohmann::json summary;
  summary_opening(summary, opt, "spheres", {static_cast<std::int64_t>(n), 0}, 1, threads_in_use());
  summary["grains"] = n;
  summary["dt"] = s.dt;
  summary["critical_period"] = s.critical.period;
  summary["critical_term"] = s.critical.term;
  summary["status"] = "running";
  if (ckpt) summary["resumed_from"] = resumed_from_json(*ckpt, world.clock);
  return summary;
}

}  // namespace

int run_dem_command(const CliOptions& opt) {
  const auto wall0 = std::chrono::steady_clock::now();
  const SceneDoc doc = SceneDoc::load(opt.scene, opt.overrides);
  const DemScene s = load_dem_scene(doc);
  if (s.bodies) return run_body_command(opt, s);
  const std::filesystem::path out = opt.out_dir();
  ensure_directory(out);

  DemSimulation sim(s);
  World& world = sim.world();
  std::optional<CheckpointReader> ckpt;
  if (opt.resume) {
    ckpt.emplace(*opt.resume);
    sim.resume(*ckpt);
  }
  const CheckpointReader* from = ckpt ? &*ckpt : nullptr;
  const std::size_t n = world.grains.n_owned;
  std::fprintf(stderr, "grainflow: %s: %zu grains, dt = %.3g s (%.3f of the critical period), %zu threads -> %s\n",
               s.file.string().c_str(), n, s.dt, s.dt / s.critical.period, threads_in_use(), out.string().c_str());
  if (ckpt) say_resuming(*ckpt, world.clock);
  nlohmann::json summary = opening_summary(opt, s, world, n, from);
  write_summary_json(out / "summary.json", summary);

  // A resumed run continues the main stage; its settling was done by the run that wrote the checkpoint.
  StageReport settle;
  try {
    if (!ckpt) settle = sim.settle(opt.quiet ? 0.0 : 2.0);
  } catch (const StabilityError& e) {
    summary["status"] = "failed";
    summary["failure"] = std::string("while settling: ") + e.what();
    summary["steps"] = 0;
    write_summary_json(out / "summary.json", summary);
    std::fprintf(stderr, "grainflow: failed while settling\ngrainflow: error: %s\n", e.what());
    return 3;
  }
  sim.step().reset_timings();
  DemObservers o;
  add_observers(o, s, out, world, from);
  RunOutcome r;
  const StageReport main = step_main_stage(opt, s, sim, o, out, from, r);
  summarise_run(summary, r, main, settle, o, sim, n, seconds_since(wall0));
  try {
    write_final_state(out / "final_state.csv", world.grains, s);
    write_summary_json(out / "summary.json", summary);
  } catch (const WriteError& e) {
    // The earlier summary.json (status "running") and final state stay as they were.
    if (r.failure.empty()) r.fail(e.what() + write_failure_fix(opt, out, ckpt || o.checkpoints->written() > 0));
    else r.fail(r.failure + "; then " + e.what());
  }
  char rate[64];
  std::snprintf(rate, sizeof rate, ": %.3g particle-steps/s", summary["particle_steps_per_second"].get<double>());
  say_done(r, world.clock.t, rate);
  if (r.failure.empty() && o.pictures && !o.pictures->last_picture().empty())
    std::fprintf(stderr, "grainflow: picture of the drum: %s\n", o.pictures->last_picture().string().c_str());
  return r.rc;
}

}  // namespace gf
