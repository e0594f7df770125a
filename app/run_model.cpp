#include "app/run_model.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>

#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "engine/atomic_file.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/summary_json.hpp"

namespace gf {

namespace {

using WallClock = std::chrono::steady_clock;

// One run in progress: its folder, the checkpoint it resumed, the summary, the observers and how it ends.
struct Run {
  Run(Model& m, const CliOptions& o, const RunPlace& p) : model(m), opt(o), place(p), out(o.out_dir()) {}
  Model& model;
  const CliOptions& opt;
  const RunPlace& place;
  std::filesystem::path out;
  WallClock::time_point wall0 = WallClock::now();
  std::optional<CheckpointReader> from;
  nlohmann::json summary;
  Schedule observers;
  CheckpointOutput* checkpoints = nullptr;  // on the process that writes
  RunOutcome outcome;
  StageReport settle, main;

  const CheckpointReader* resumed() const { return from ? &*from : nullptr; }
  // Whether a checkpoint is on disk to go on from: this run's, or the one it resumed.
  bool have_checkpoint() const { return from.has_value() || (checkpoints && checkpoints->written() > 0); }
  double progress_seconds() const { return place.writer && !opt.quiet ? 2.0 : 0.0; }
  // Runs `body`, recording what it throws (run_outcome.hpp).
  template <class Body>
  void guard(Body&& body) {
    guarded(outcome, opt, out, [this] { return have_checkpoint(); }, std::forward<Body>(body));
  }
};

void together(const RunPlace& place, const std::function<void()>& phase) {
  if (place.together) place.together(phase);
  else phase();
}

// The folder, the resumed state, the opening line and summary.json's opening.
void open_run(Run& run) {
  Model& m = run.model;
  if (run.place.writer) ensure_directory(run.out);
  if (run.opt.resume) {
    run.from.emplace(*run.opt.resume);
    m.resume(*run.from);
  }
  if (!run.place.writer) return;
  std::fprintf(stderr, "grainflow: %s -> %s\n", m.opening(threads_in_use(), run.place.ranks).c_str(),
               run.out.string().c_str());
  if (const std::string w = m.warning(); !w.empty()) std::fprintf(stderr, "grainflow: warning: %s\n", w.c_str());
  if (run.from) say_resuming(*run.from, m.world().clock);
  summary_opening(run.summary, run.opt, m.kind(), m.counts(), run.place.ranks, threads_in_use());
  m.open_summary(run.summary);
  run.summary["status"] = "running";
  if (run.from) run.summary["resumed_from"] = resumed_from_json(*run.from, m.world().clock);
  write_summary_json(run.out / "summary.json", run.summary);
}

// The settling stage of a run that does not resume (the run that wrote a checkpoint settled). Returns
// false when it failed: the summary says so, and the run ends with exit status 3.
bool settle_stage(Run& run) {
  if (run.from) return true;
  try {
    run.settle = run.model.settle(run.progress_seconds());
  } catch (const StabilityError& e) {
    if (!run.place.writer) return false;
    run.summary["status"] = "failed";
    run.summary["failure"] = std::string("while settling: ") + e.what();
    run.summary["steps"] = 0;
    write_summary_json(run.out / "summary.json", run.summary);
    std::fprintf(stderr, "grainflow: failed while settling\ngrainflow: error: %s\n", e.what());
    return false;
  }
  return true;
}

// The main stage with its observers. --steps and the scene's duration count the whole main stage, so
// a resumed run ends where the uninterrupted one would.
void main_stage(Run& run) {
  Model& m = run.model;
  World& world = m.world();
  StageOptions so;
  so.label = "run";
  so.progress_seconds = run.progress_seconds();
  so.steps = std::max<std::int64_t>(0, (run.opt.steps ? *run.opt.steps : m.last_step()) - world.clock.step);
  so.observe = run.place.writer ? &run.observers : nullptr;
  so.observe_start = !run.from || m.observe_resumed_start();
  so.rows = [&m](const World& w) { return m.rows(w); };
  const std::int64_t first = world.clock.step;
  const auto run0 = WallClock::now();
  run.guard([&] {
    run.main = run_stage(world, m.step(), so);
    if (run.main.interrupted) run.outcome.status = "interrupted";
  });
  if (run.outcome.failed()) {  // a stage that threw: the steps it took, and its wall time
    run.main.steps = world.clock.step - first;
    run.main.wall_seconds = seconds_since(run0);
  }
  run.outcome.steps = run.main.steps;
  run.outcome.wall = run.main.wall_seconds;
}

// On the process that writes: the checkpoint at the end, the outputs closed, the final state's analyses.
void end_outputs(Run& run) {
  Model& m = run.model;
  if (m.checkpoint_at_end())
    run.guard([&] { run.outcome.checkpoint_file = run.checkpoints->write(m.world()).string(); });
  run.guard([&] { m.finish_outputs(); });
  run.guard([&] { m.final_results(run.out, run.summary); });
}

void close_summary(Run& run) {
  Model& m = run.model;
  const World& world = m.world();
  const StageReport& main = run.main;
  // A stage that threw reports its steps but not the rows stepped: those of the end, then.
  const double stepped = main.particle_steps > 0 ? main.particle_steps : static_cast<double>(main.steps) * m.rows(world);
  nlohmann::json& s = run.summary;
  s["status"] = run.outcome.status;
  if (!run.outcome.failure.empty()) s["failure"] = run.outcome.failure;
  s["settle"] = {{"steps", run.settle.steps}, {"wall_seconds", run.settle.wall_seconds}};
  s["steps"] = world.clock.step;
  s["steps_this_run"] = main.steps;
  s["simulated_time"] = world.clock.t;
  s["wall_seconds"] = main.wall_seconds;
  s["total_wall_seconds"] = seconds_since(run.wall0);
  s["particle_steps_per_second"] = main.wall_seconds > 0 ? stepped / main.wall_seconds : 0.0;
  s["checkpoints_written"] = run.checkpoints->written();
  if (!run.outcome.checkpoint_file.empty()) s["checkpoint"] = run.outcome.checkpoint_file;
  summary_counts_at_end(s, m.counts());
  s["time_per_system"] = timings_json({&m.step(), &run.observers});
  m.close_summary(s, main);
}

// The final files and summary.json; a write that fails leaves the earlier ones as they were.
void write_end(Run& run) {
  try {
    run.model.write_final_files(run.out);
    write_summary_json(run.out / "summary.json", run.summary);
  } catch (const WriteError& e) {
    RunOutcome& r = run.outcome;
    if (r.failure.empty()) r.fail(e.what() + write_failure_fix(run.opt, run.out, run.have_checkpoint()));
    else r.fail_also(e.what());
  }
}

void say_end(Run& run) {
  const double rate = run.summary["particle_steps_per_second"].get<double>();
  char line[96];
  std::snprintf(line, sizeof line, ": %.3g %s", rate, std::string(run.model.rate_unit()).c_str());
  say_done(run.outcome, run.model.world().clock.t, line);
  if (run.outcome.failure.empty())
    if (const std::string words = run.model.last_words(); !words.empty())
      std::fprintf(stderr, "grainflow: %s\n", words.c_str());
}

}  // namespace

int run_model(Model& model, const CliOptions& opt, const RunPlace& place) {
  Run run(model, opt, place);
  together(place, [&] { open_run(run); });
  if (!settle_stage(run)) return 3;
  model.step().reset_timings();
  together(place, [&] {
    if (place.writer) run.checkpoints = &model.observe(run.observers, run.out, run.resumed());
  });
  main_stage(run);
  if (!place.writer) return run.outcome.rc;  // the others' failures are the writer's to report
  end_outputs(run);
  close_summary(run);
  write_end(run);
  say_end(run);
  return run.outcome.rc;
}

}  // namespace gf
