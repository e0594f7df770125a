#include "app/dem_body_app.hpp"

#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <nlohmann/json.hpp>

#include <tbb/global_control.h>

#include "engine/atomic_file.hpp"
#include "engine/run_loop.hpp"
#include "systems/analysis/body_repose.hpp"
#include "systems/analysis/packing.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/output/body_outputs.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/setup/dem_body_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace gf {

namespace {

// Empty unless dt passes dt_safety of the rim contacts' period (BodiesSpec::rim): then what that
// risks and the step that keeps to it.
std::string rim_warning(const DemScene& s) {
  const CriticalStep& rim = s.bodies->rim;
  if (!(s.dt > s.dt_safety * rim.period)) return "";
  return "dt is " + short_number(s.dt / rim.period) + " of the period of a contact at a body's rim (" + rim.term +
         "; limit " + short_number(s.dt_safety) + "): flat grains pressed at several rim points at once, such as "
         "plates stacked face to face, can rock unstably (bodies jumping from step to step, kinetic-energy bursts in "
         "a settled bed); to be safe give run.dt = " + short_number(s.dt_safety * rim.period) + " or less";
}

struct BodyCounts {
  std::size_t moving = 0, fixed = 0, timed = 0, members = 0;
};

BodyCounts count_bodies(const DemScene& s, World& w) {
  BodyCounts c;
  for (const BodyPlacement& p : s.bodies->placed) {
    c.fixed += p.fixed;
    c.moving += !p.fixed;
    c.timed += p.remove_at >= 0;
  }
  c.members = w.tables.get<Members>().n;
  return c;
}

// What the body frames write of each body beside its state.
BodyFrameLabels frame_labels(const BodiesSpec& b) {
  BodyFrameLabels l;
  for (const BodyShape& sh : b.shapes) {
    l.shape_name.push_back(sh.name);
    l.shape_axes.emplace_back(sh.props.axes);
  }
  for (const BodyPlacement& p : b.placed) {
    l.shape.push_back(p.shape);
    l.group.push_back(p.group);
  }
  return l;
}

// The pictures' colours per body row and the legend for the PNG's Comment entry.
std::vector<Rgb> picture_colours(const DemScene& s, const std::vector<int>& layers, std::string& legend) {
  const BodiesSpec& b = *s.bodies;
  std::vector<Rgb> c(b.placed.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    c[i] = b.output.colour_by_layer ? layer_colour(std::max(layers[i], 0)) : group_colour(b.placed[i].group);
  legend = b.output.colour_by_layer
               ? "five layers of equal counts by height at t = 0, lowest first: blue #0072B2, vermillion #D55E00, "
                 "blue, vermillion, blue; fixed bodies grey"
               : "by [[bodies]] group, Okabe-Ito palette from group 0: blue, vermillion, bluish green, orange, "
                 "reddish purple, sky blue, yellow; fixed bodies grey";
  return c;
}

// The outer edges of a shape: its cores' bounding box grown by the dilation radius on every side.
std::array<double, 3> outer_edges(const ShapeSpec& shape) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& part : shape.parts)
    for (const Eigen::Vector3d& v : part) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
  return {hi.x() - lo.x() + 2 * shape.radius, hi.y() - lo.y() + 2 * shape.radius, hi.z() - lo.z() + 2 * shape.radius};
}

// The packing of the final bed (systems/analysis/packing.hpp: bed_packing), sampled on voxels of a
// sixth of the thinnest moving shape's smallest edge. Its interior lies half a grain length (the
// largest outer edge of any moving shape) inside the bed's walls, above its floor and below its free
// surface: for the seed's flat letters three stroke widths, three letters lying flat on a wall. How
// the fraction depends on that choice is in "by_margin" (a quarter, a half and a whole grain length)
// and in packing.csv, the fraction per voxel layer from the floor: height (m, the layer's centre
// above the floor), interior (within the interior's columns), whole (across the bed's full extent).
// Returns summary.json's "packing" entry.
// The angle of repose of each [[analysis.repose]] heap in the final state (body_repose.hpp), in
// degrees, per flank with its slope, the columns fitted and their span; summary.json's "repose".
nlohmann::json final_repose(const DemScene& s, World& world) {
  const Gravity& g = world.resources.get<Gravity>();
  const double norm = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
  nlohmann::json out = nlohmann::json::object();
  if (s.bodies->output.repose.empty() || !(norm > 0)) return out;
  const V3<double> up{-g.x / norm, -g.y / norm, -g.z / norm};
  auto flank = [](const ReposeFlank& f) {
    nlohmann::json j = {{"columns", f.columns}, {"s_from", f.s_from}, {"s_to", f.s_to}};
    j["angle_deg"] = std::isfinite(f.angle) ? nlohmann::json(f.angle * 180.0 / std::numbers::pi) : nlohmann::json();
    j["slope"] = std::isfinite(f.slope) ? nlohmann::json(f.slope) : nlohmann::json();
    return j;
  };
  for (const ReposeSpec& spec : s.bodies->output.repose) {
    const Repose r = body_repose(world.tables.get<Bodies>(), world.tables.get<Members>(), up, spec);
    nlohmann::json j = {{"first", flank(r.first)}};
    if (spec.geometry != ReposeSpec::Geometry::heap) j["second"] = flank(r.second);
    j["extreme_height"] = std::isfinite(r.extreme_height) ? nlohmann::json(r.extreme_height) : nlohmann::json();
    j["column"] = spec.settings.column;
    out[spec.name] = j;
  }
  return out;
}

nlohmann::json final_packing(const DemScene& s, World& world, const std::filesystem::path& out) {
  const Gravity& g = world.resources.get<Gravity>();
  const double gv[3] = {g.x, g.y, g.z};
  int up = -1, along = 0;
  for (int d = 0; d < 3; ++d)
    if (gv[d] != 0.0) {
      up = d;
      ++along;
    }
  if (along != 1) return {{"valid", false}, {"reason", "gravity is not along one axis"}};
  double length = 0;
  for (const BodyPlacement& p : s.bodies->placed)
    if (!p.fixed)
      for (const double e : outer_edges(s.bodies->shapes[p.shape].shape)) length = std::max(length, e);
  const double h = s.bodies->output.overlap_scale / 6.0;
  if (!(length > 0) || !std::isfinite(h)) return {{"valid", false}, {"reason", "no moving bodies"}};
  auto vec = [](const std::array<double, 3>& v) { return nlohmann::json::array({v[0], v[1], v[2]}); };
  auto measure = [&](double margin, BedPacking& p) {
    p = bed_packing(world.tables.get<Bodies>(), world.tables.get<Members>(), up, gv[up] < 0 ? 1 : -1, margin, h);
    nlohmann::json j = {{"valid", p.valid}, {"margin", margin}};
    if (!p.valid) {
      j["reason"] = p.reason;
      return j;
    }
    j["fraction"] = p.interior.fraction;
    j["interior_voxels"] = p.interior.voxels;
    j["region"] = {{"lo", vec(p.lo)}, {"hi", vec(p.hi)}};
    return j;
  };
  BedPacking p, other;
  nlohmann::json j = measure(0.5 * length, p);
  j["by_margin"] = nlohmann::json::array({measure(0.25 * length, other), j, measure(length, other)});
  j["grain_length"] = length;
  j["voxel"] = h;
  j["up_axis"] = up;
  if (!p.valid) return j;
  j["whole_bed_fraction"] = p.whole.fraction;
  j["bed"] = {{"lo", vec(p.bed_lo)}, {"hi", vec(p.bed_hi)}};
  j["floor"] = p.floor;
  j["surface"] = p.surface;
  j["bed_depth"] = std::abs(p.surface - p.floor);
  std::string csv = "height,interior,whole\n";
  char line[96];
  for (const BedPacking::Layer& l : p.layers) {
    std::snprintf(line, sizeof line, "%.6g,%.6g,%.6g\n", l.height, l.interior, l.whole);
    csv += line;
  }
  write_file_atomic(out / "packing.csv", csv);
  return j;
}

}  // namespace

int check_body_command(const CliOptions& opt, const DemScene& s) {
  (void)opt;
  DemSimulation sim(s);
  sim.prime();
  const BodyCounts c = count_bodies(s, sim.world());
  std::printf("scene %s: valid\n", s.file.string().c_str());
  std::printf("model: composite grains (rigid unions of dilated convex polyhedra); contact law %s\n", s.law.c_str());
  std::printf("bodies: %zu moving, %zu fixed (%zu removed at a time); members: %zu; shapes: %zu; plane walls: %zu\n",
              c.moving, c.fixed, c.timed, c.members, s.bodies->shapes.size(), s.walls.size());
  for (const BodyShape& sh : s.bodies->shapes)
    std::printf("  shape %s: %zu parts, r = %.4g m, mass %.6g kg, volume %.6g m^3, moments %.4g %.4g %.4g kg m^2\n",
                sh.name.c_str(), sh.shape.parts.size(), sh.shape.radius, sh.props.mass, sh.props.volume,
                sh.props.moments.x(), sh.props.moments.y(), sh.props.moments.z());
  std::printf("systems per step (with the systems each waits for):\n%s", sim.step().describe().c_str());
  std::printf("observers: body_series_output, body_frame_output, body_picture_output\n");
  std::printf("critical step: smallest time-step term %.4g s (%s); dt = %.4g s = %.3f of it (limit %.3f)%s\n",
              s.critical.period, s.critical.term.c_str(), s.dt, s.dt / s.critical.period, s.dt_safety,
              s.allow_unstable_dt && s.dt > s.dt_safety * s.critical.period ? " OVERRIDDEN" : "");
  std::printf("rim contacts: smallest time-step term %.4g s (%s, each body's rim mass); dt = %.3f of it%s\n",
              s.bodies->rim.period, s.bodies->rim.term.c_str(), s.dt / s.bodies->rim.period,
              rim_warning(s).empty() ? "" : (" -- " + rim_warning(s)).c_str());
  std::printf("steps: %lld settling + %lld main (%.4g s simulated)\n", static_cast<long long>(s.settle_steps()),
              static_cast<long long>(s.main_steps()), s.duration);
  const BodyContactState& st = sim.world().resources.get<BodyContactState>();
  std::printf("initial contacts: %zu member pairs (%zu with fixed bodies), %zu with plane walls; list pairs %zu\n",
              st.last.pair_contacts, st.last.fixed_contacts, st.last.wall_contacts, st.list.pairs());
  if (s.output.checkpoint_interval > 0)
    std::printf("checkpoints: every %.4g s of the main stage%s\n", s.output.checkpoint_interval,
                s.output.checkpoint_at_end ? " and at its end" : "");
  else
    std::printf("checkpoints: %s\n", s.output.checkpoint_at_end ? "at the end of the run" : "none");
  return 0;
}

namespace {

// One run of a body scene: the simulation, its checkpoint when resumed, the observers (on the
// process that writes) and the summary.
struct BodyRun {
  std::filesystem::path out;
  std::unique_ptr<DemSimulation> sim;
  BodyCounts counts;
  std::optional<CheckpointReader> ckpt;
  nlohmann::json summary;
  Schedule observe;
  BodySeriesOutput* series = nullptr;
  BodyFrameOutput* frames = nullptr;
  BodyPictureOutput* pictures = nullptr;
  CheckpointOutput* checkpoints = nullptr;
};

void together(const BodyRunHooks& hooks, const std::function<void()>& f) {
  if (hooks.together) hooks.together(f);
  else f();
}

// The simulation (restored from the checkpoint when resumed) and, on the writer, the output folder
// and the summary's opening.
void start_body_run(BodyRun& run, const CliOptions& opt, const DemScene& s, const BodyRunHooks& hooks) {
  run.out = opt.out_dir();
  if (hooks.writer) ensure_directory(run.out);
  run.sim = std::make_unique<DemSimulation>(s);
  World& world = run.sim->world();
  if (hooks.install) hooks.install(world);
  run.counts = count_bodies(s, world);
  if (opt.resume) {
    run.ckpt.emplace(*opt.resume);
    restore_body_state(*run.ckpt, world, s);
  }
  if (!hooks.writer) return;
  std::fprintf(stderr, "grainflow: %s: %zu moving and %zu fixed bodies (%zu members), dt = %.3g s (%.3f of the "
               "critical period), %zu threads%s -> %s\n",
               s.file.string().c_str(), run.counts.moving, run.counts.fixed, run.counts.members, s.dt,
               s.dt / s.critical.period, threads_in_use(),
               hooks.ranks > 1 ? (" on each of " + std::to_string(hooks.ranks) + " ranks").c_str() : "",
               run.out.string().c_str());
  if (!rim_warning(s).empty()) std::fprintf(stderr, "grainflow: warning: %s\n", rim_warning(s).c_str());
  nlohmann::json& summary = run.summary;
  summary_opening(summary, opt, "bodies", {static_cast<std::int64_t>(run.counts.moving + run.counts.fixed), 0},
                  hooks.ranks, threads_in_use());
  summary["bodies"] = {{"moving", run.counts.moving}, {"fixed", run.counts.fixed}, {"members", run.counts.members}};
  for (const BodyShape& sh : s.bodies->shapes)
    summary["shapes"][sh.name] = {{"parts", sh.shape.parts.size()}, {"mass", sh.props.mass}, {"volume", sh.props.volume},
                                  {"moments", {sh.props.moments[0], sh.props.moments[1], sh.props.moments[2]}}};
  summary["dt"] = s.dt;
  summary["critical_period"] = s.critical.period;
  summary["critical_term"] = s.critical.term;
  summary["rim_critical_period"] = s.bodies->rim.period;
  summary["rim_critical_term"] = s.bodies->rim.term;
  summary["status"] = "running";
  if (run.ckpt) {
    summary["resumed_from"] = resumed_from_json(*run.ckpt, world.clock);
    say_resuming(*run.ckpt, world.clock);
  }
  write_summary_json(run.out / "summary.json", summary);
}

// The observers of the main stage, from the state at its start (layers, the remaining fraction's
// denominator, the pictures' window); a resumed run takes them and the observers' state from its
// checkpoint.
void make_body_observers(BodyRun& run, const DemScene& s) {
  World& world = run.sim->world();
  const Bodies& bodies = world.tables.get<Bodies>();
  const BodyOutputSpec& bo = s.bodies->output;
  std::vector<int> layers;
  std::uint64_t initial_moving = 0;
  const double lowest = bo.has_sink ? bo.sink_height : std::numeric_limits<double>::quiet_NaN();
  BodyView view;
  const std::optional<CheckpointReader>& ckpt = run.ckpt;
  if (ckpt) {
    ckpt->vector("body_run.layers", layers);
    initial_moving = ckpt->value<std::uint64_t>("body_run.initial_moving");
    view = ckpt->value<BodyView>("body_run.view");
    if (layers.size() != bodies.n) ckpt->fail("its layers are not one per body", "resume with the scene of the run that wrote it");
  } else {
    layers = body_layers(bodies, world.resources.get<Gravity>());
    for (std::size_t i = 0; i < bodies.n; ++i) initial_moving += bodies.moving(i);
    view = body_view(bodies, world.tables.get<Members>(), bo.view_axis, bo.picture_size, lowest);
  }
  Schedule& observe = run.observe;
  world.resources.emplace<BodySeriesRow>();
  BodySeriesSettings ss;
  if (s.output.series_interval > 0) ss.csv = run.out / "series.csv";
  ss.interval = s.output.series_interval > 0 ? s.output.series_interval : 1000 * s.dt;
  ss.overlap_scale = bo.overlap_scale;
  if (bo.has_outlet) ss.outlet_height = bo.outlet_height;
  ss.initial_moving = initial_moving;
  if (ckpt) ss.resume_rows = ckpt->value<std::uint64_t>("body_series_output.rows");
  run.series = &observe.emplace<BodySeriesOutput>(ss);
  if (s.output.frame_interval > 0)
    run.frames = &observe.emplace<BodyFrameOutput>(run.out, s.output.frame_interval, frame_labels(*s.bodies), layers);
  if (bo.picture_interval > 0) {
    std::string legend;
    std::vector<Rgb> colours = picture_colours(s, layers, legend);
    run.pictures = &observe.emplace<BodyPictureOutput>(run.out / "pictures", bo.picture_interval, view,
                                                       std::move(colours), std::move(legend));
  }
  std::vector<const Checkpointable*> parts{run.series};
  if (run.frames) parts.push_back(run.frames);
  if (run.pictures) parts.push_back(run.pictures);
  run.checkpoints = &observe.emplace<CheckpointOutput>(
      CheckpointSettings{run.out, s.output.checkpoint_interval, s.output.checkpoint_keep_all},
      [&s, layers, initial_moving, view](CheckpointWriter& w, World& wd) {
        save_body_state(w, wd, s);
        w.vector("body_run.layers", layers);
        w.value("body_run.initial_moving", initial_moving);
        w.value("body_run.view", view);
      },
      parts);
  observe.build(world);
  if (!ckpt) return;
  run.series->restore(*ckpt);
  if (run.frames) {
    if (!ckpt->has("body_frame_output.next"))
      ckpt->fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    run.frames->restore(*ckpt);
  }
  if (run.pictures) {
    if (!ckpt->has("body_picture_output.next"))
      ckpt->fail("the run that wrote it drew no pictures", "resume with output.picture_interval = 0, as that run had");
    run.pictures->restore(*ckpt);
  }
  run.checkpoints->restore(*ckpt);
}

// After the main stage, on the writer: the last checkpoint, the outputs closed, the final bed's
// packing and repose, and the summary. Returns the exit status.
int finish_body_run(const CliOptions& opt, BodyRun& run, const DemScene& s, const StageReport& settle,
                    const StageReport& main, RunOutcome& r, std::chrono::steady_clock::time_point wall0) {
  World& world = run.sim->world();
  const auto have_checkpoint = [&] { return run.ckpt.has_value() || run.checkpoints->written() > 0; };
  if (s.output.checkpoint_at_end)
    guarded(r, opt, run.out, have_checkpoint, [&] { r.checkpoint_file = run.checkpoints->write(world).string(); });
  guarded(r, opt, run.out, have_checkpoint, [&] {
    run.series->finish(world);
    if (run.frames) run.frames->finish(world);
  });
  nlohmann::json packing, repose;
  if (!r.failed()) {
    try {
      packing = final_packing(s, world, run.out);
      repose = final_repose(s, world);
    } catch (const std::exception& e) {
      r.fail(std::string("the final packing or repose: ") + e.what());
    }
  }
  const double bsps = main.wall_seconds > 0 ? static_cast<double>(main.steps) * run.counts.moving / main.wall_seconds : 0.0;
  const BodySeriesRow& row = world.resources.get<BodySeriesRow>();
  nlohmann::json& summary = run.summary;
  summary["status"] = r.status;
  if (!r.failure.empty()) summary["failure"] = r.failure;
  summary["settle"] = {{"steps", settle.steps}, {"wall_seconds", settle.wall_seconds}};
  summary["steps"] = world.clock.step;
  summary["simulated_time"] = world.clock.t;
  summary["wall_seconds"] = main.wall_seconds;
  summary["total_wall_seconds"] = seconds_since(wall0);
  summary["body_steps_per_second"] = bsps;
  summary["steps_this_run"] = main.steps;
  summary["checkpoints_written"] = run.checkpoints->written();
  if (!r.checkpoint_file.empty()) summary["checkpoint"] = r.checkpoint_file;
  summary["member_list_rebuilds"] = world.resources.get<BodyContactState>().rebuilds;
  summary["frames"] = run.frames ? run.frames->frames() : 0;
  summary["pictures"] = run.pictures ? run.pictures->pictures() : 0;
  summary["final"] = {{"time", row.time},
                      {"ke_translational", row.ke_translational},
                      {"ke_rotational", row.ke_rotational},
                      {"contacts", row.contacts},
                      {"wall_contacts", row.wall_contacts},
                      {"max_overlap_ratio", row.max_overlap_ratio},
                      {"moving", row.moving}};
  if (s.bodies->output.has_outlet) summary["final"]["remaining_fraction"] = number_or_null(row.remaining_fraction);
  if (!packing.is_null()) summary["packing"] = packing;
  if (!repose.empty()) summary["repose"] = repose;
  summary_counts_at_end(summary, {static_cast<std::int64_t>(run.counts.moving + run.counts.fixed), 0});
  summary["time_per_system"] = timings_json({&run.sim->step(), &run.observe});
  try {
    write_summary_json(run.out / "summary.json", summary);
  } catch (const WriteError& e) {
    // The earlier summary.json (status "running") stays as it was.
    if (r.failure.empty()) r.fail(e.what() + write_failure_fix(opt, run.out, have_checkpoint()));
    else r.fail_also(e.what());
  }
  r.steps = main.steps;
  r.wall = main.wall_seconds;
  char rate[64];
  std::snprintf(rate, sizeof rate, ": %.3g body-steps/s", bsps);
  say_done(r, world.clock.t, rate);
  if (r.failure.empty() && run.pictures && !run.pictures->last_picture().empty())
    std::fprintf(stderr, "grainflow: last picture: %s\n", run.pictures->last_picture().string().c_str());
  return r.rc;
}

}  // namespace

int run_body_command(const CliOptions& opt, const DemScene& s, const BodyRunHooks& hooks) {
  const auto wall0 = std::chrono::steady_clock::now();
  BodyRun run;
  together(hooks, [&] { start_body_run(run, opt, s, hooks); });
  World& world = run.sim->world();
  const bool progress = hooks.writer && !opt.quiet;

  // A resumed run continues the main stage; its settling was done by the run that wrote the checkpoint.
  StageReport settle;
  try {
    if (!run.ckpt) settle = run.sim->settle(progress ? 2.0 : 0.0);
  } catch (const StabilityError& e) {
    if (!hooks.writer) return 3;
    run.summary["status"] = "failed";
    run.summary["failure"] = std::string("while settling: ") + e.what();
    run.summary["steps"] = 0;
    write_summary_json(run.out / "summary.json", run.summary);
    std::fprintf(stderr, "grainflow: failed while settling\ngrainflow: error: %s\n", e.what());
    return 3;
  }
  run.sim->step().reset_timings();
  together(hooks, [&] {
    if (hooks.writer) make_body_observers(run, s);
  });

  StageOptions so;
  so.progress_seconds = progress ? 2.0 : 0.0;
  so.label = "run";
  so.rows = [n = static_cast<double>(run.counts.moving)](const World&) { return n; };  // body-steps
  // --steps and the scene's duration count the whole main stage, so a resumed run ends where the
  // uninterrupted one would.
  so.steps = std::max<std::int64_t>(0, (opt.steps ? *opt.steps : s.main_steps()) - world.clock.step);
  so.observe = hooks.writer ? &run.observe : nullptr;
  StageReport main;
  RunOutcome r;
  const std::int64_t first_step = world.clock.step;
  const auto run0 = std::chrono::steady_clock::now();
  // Only the writer holds checkpoints; the other ranks' failures are the writer's to report.
  const auto have_checkpoint = [&] {
    return run.ckpt.has_value() || (run.checkpoints && run.checkpoints->written() > 0);
  };
  guarded(r, opt, run.out, have_checkpoint, [&] {
    main = run_stage(world, run.sim->step(), so);
    if (main.interrupted) r.status = "interrupted";
  });
  if (r.failed()) {
    main.steps = world.clock.step - first_step;
    main.wall_seconds = seconds_since(run0);
  }
  if (!hooks.writer) return r.rc;
  return finish_body_run(opt, run, s, settle, main, r, wall0);
}

}  // namespace gf
