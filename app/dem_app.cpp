// `grainflow run` and `grainflow check` for DEM scenes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/dem_body_app.hpp"
#include "app/run_model.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/contact/laws.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/output/layer_output.hpp"
#include "systems/output/picture_legend.hpp"
#include "systems/output/residence_csv.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_output_settings.hpp"
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
  for (std::size_t k = 0; k < s.species.size(); ++k) {
    const SpeciesSpec& sp = s.species[k];
    std::printf("species %zu '%s': diameter %s, density %s kg/m^3%s\n", k, sp.name.c_str(),
                sp.size.describe(length_label).c_str(), short_number(sp.density).c_str(),
                sp.size.is_fixed() ? "" : " (each grain draws its own; contacts scaled to their grains)");
  }
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

void add_observers(DemObservers& o, Schedule& schedule, const DemScene& s, const std::filesystem::path& out,
                   World& world, const CheckpointReader* ckpt) {
  world.resources.emplace<SeriesRow>();
  SeriesSettings ss = scene_series_settings(s, out);
  if (ckpt) {
    ss.resume_rows = ckpt->value<std::uint64_t>("series_output.rows");
    ss.resume_time = world.clock.t;
  }
  o.series = &schedule.emplace<SeriesOutput>(ss);
  if (s.output.frame_interval > 0) o.frames = &schedule.emplace<FrameOutput>(out, s.output.frame_interval, s.output.fields);
  if (scene_draws_pictures(s)) o.pictures = &schedule.emplace<PictureOutput>(scene_picture_settings(s, out));
  if (!s.flow.outlets.empty()) {
    std::optional<std::size_t> keep;
    if (ckpt) keep = ckpt->value<std::uint64_t>("residence_output.rows");
    o.residence = &schedule.emplace<ResidenceOutput>(out / "residence.csv", keep);
  }
  if (s.layers) {
    std::optional<std::size_t> keep;
    if (ckpt) keep = ckpt->value<std::uint64_t>("layer_output.rows");
    o.layers = &schedule.emplace<LayerOutput>(out / "layers.csv", *s.layers, keep);
  }
  std::vector<const Checkpointable*> parts{o.series};
  if (o.layers) parts.push_back(o.layers);
  if (o.frames) parts.push_back(o.frames);
  if (o.pictures) parts.push_back(o.pictures);
  if (o.residence) parts.push_back(o.residence);
  o.checkpoints = &schedule.emplace<CheckpointOutput>(
      CheckpointSettings{out, s.output.checkpoint_interval, s.output.checkpoint_keep_all},
      [&s](CheckpointWriter& w, World& wd) { save_dem_state(w, wd, s); }, parts);
  schedule.build(world);
  if (ckpt) restore_observers(o, *ckpt);
}

// Spheres on one process (DemSimulation), for the run skeleton (run_model.hpp).
class SphereModel final : public ScheduledModel {
 public:
  explicit SphereModel(const DemScene& s) : s_(s), sim_(s) {}

  std::string_view kind() const override { return "spheres"; }
  World& world() override { return sim_.world(); }
  Schedule& step() override { return sim_.step(); }
  RunCounts counts() override { return {static_cast<std::int64_t>(sim_.grains().n_owned), 0}; }

  void restore(const CheckpointReader& from) override { sim_.resume(from); }
  std::string opening(std::size_t threads, int) override {
    char line[256];
    std::snprintf(line, sizeof line, "%zu grains, dt = %.3g s (%.3f of the critical period), %zu threads",
                  sim_.world().grains.n_owned, s_.dt, s_.dt / s_.critical.period, threads);
    return s_.file.string() + ": " + line;
  }
  void open_summary(nlohmann::json& summary) override {
    summary["grains"] = sim_.world().grains.n_owned;
    summary["dt"] = s_.dt;
    summary["critical_period"] = s_.critical.period;
    summary["critical_term"] = s_.critical.term;
  }
  StageReport settle(double progress_seconds) override { return sim_.settle(progress_seconds); }
  void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) override {
    add_observers(o_, observers, s_, out, sim_.world(), from);
    checkpoints_ = o_.checkpoints;
  }

  std::int64_t last_step() const override { return s_.main_steps(); }
  bool checkpoint_at_end() const override { return s_.output.checkpoint_at_end; }
  double rows(const World& w) const override { return static_cast<double>(w.grains.n_owned); }

  void finish_outputs() override {
    o_.series->finish(sim_.world());
    if (o_.frames) o_.frames->finish(sim_.world());
  }
  void close_summary(nlohmann::json& summary, const StageReport&) override {
    World& world = sim_.world();
    const BroadphaseState& broadphase = world.resources.get<BroadphaseState>();
    summary["neighbor_rebuilds"] = broadphase.rebuilds;
    // Checks where some grain had moved past skin/2 but no pair missing from the list touched.
    summary["neighbor_list_kept"] = broadphase.cover.kept;
    summary["frames"] = o_.frames ? o_.frames->frames() : 0;
    summary["pictures"] = o_.pictures ? o_.pictures->pictures() : 0;
    summary["final"] = final_row_json(world.resources.get<SeriesRow>());
    if (const FlowState* f = world.resources.find<FlowState>())
      summary["flow"] = flow_json(*f, world.grains, o_.residence);
  }
  void write_final_files(const std::filesystem::path& out) override {
    write_final_state(out / "final_state.csv", sim_.world().grains);
  }
  std::string last_words() const override {
    if (!o_.pictures || o_.pictures->last_picture().empty()) return "";
    return "picture of the drum: " + o_.pictures->last_picture().string();
  }

 private:
  const DemScene& s_;
  DemSimulation sim_;
  DemObservers o_;
};

}  // namespace

int run_dem_command(const CliOptions& opt) {
  const SceneDoc doc = SceneDoc::load(opt.scene, opt.overrides);
  const DemScene s = load_dem_scene(doc);
  if (s.bodies) {
    BodyRunHooks hooks;
    hooks.scene_json = doc.resolved_json();
    return run_body_command(opt, s, hooks);
  }
  SphereModel model(s);
  model.scene_json = doc.resolved_json();
  return run_model(model, opt);
}

}  // namespace gf
