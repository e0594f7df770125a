#include "app/run_model.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <utility>

#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "engine/atomic_file.hpp"
#include "systems/output/checkpoint_output.hpp"
#include "systems/output/summary_json.hpp"

namespace gf {

std::unique_ptr<CheckpointReader> Model::resume(const std::filesystem::path& file) {
  auto from = std::make_unique<CheckpointReader>(file);
  restore(*from);
  return from;
}

std::filesystem::path Model::go_on_from(const std::filesystem::path& out, const CheckpointReader* resumed) const {
  if (checkpoints_written() > 0) return out / "checkpoints" / "checkpoint.gfc";
  return resumed ? resumed->file() : std::filesystem::path();
}

std::string Model::rate(const nlohmann::json& summary) const {
  char text[64];
  std::snprintf(text, sizeof text, "%.3g particle-steps/s", summary["particle_steps_per_second"].get<double>());
  return text;
}

std::filesystem::path ScheduledModel::write_checkpoint() { return checkpoints_->write(world()); }

std::size_t ScheduledModel::checkpoints_written() const { return checkpoints_ ? checkpoints_->written() : 0; }

std::string RunPlace::command() const {
  if (program == "grainflow") return "grainflow run";
  return "mpiexec -n " + std::to_string(ranks) + " " + program + " run";
}

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
  std::unique_ptr<CheckpointReader> from;
  nlohmann::json summary;
  Schedule observers;
  RunOutcome outcome;
  StageReport settle, main;

  std::filesystem::path go_on_from() const { return model.go_on_from(out, from.get()); }
  double progress_seconds() const { return place.writer && !opt.quiet ? 2.0 : 0.0; }
  const char* program() const { return place.program.c_str(); }
  // Runs `body` unless the run failed already, recording what it throws: a write that failed with
  // how to go on, anything else with its message.
  template <class Body>
  void guard(Body&& body) {
    if (outcome.failed()) return;
    try {
      std::forward<Body>(body)();
    } catch (const WriteError& e) {
      outcome.fail(e.what() + write_failure_fix(place.command(), opt, out, go_on_from()));
    } catch (const std::exception& e) {
      outcome.fail(e.what());
    }
  }
};

void together(const RunPlace& place, const std::function<void()>& phase) {
  if (place.together) place.together(phase);
  else phase();
}

// The folder and the resumed state.
void open_run(Run& run) {
  if (run.place.writer) ensure_directory(run.out);
  if (run.opt.resume) run.from = run.model.resume(*run.opt.resume);
}

// The opening line and summary.json's opening, on the process that writes.
void open_summary(Run& run, RunCounts at_start) {
  Model& m = run.model;
  std::fprintf(stderr, "%s: %s -> %s\n", run.program(), m.opening(threads_in_use(), run.place.ranks).c_str(),
               run.out.string().c_str());
  if (const std::string w = m.warning(); !w.empty()) std::fprintf(stderr, "%s: warning: %s\n", run.program(), w.c_str());
  if (run.opt.resume) say_resuming(run.place.program, *run.opt.resume, m.world().clock, m.resumed_note());
  summary_opening(run.summary, run.opt, m.kind(), at_start, run.place.ranks, threads_in_use());
  if (!m.scene_json.empty()) run.summary["scene_resolved"] = nlohmann::json::parse(m.scene_json);
  m.open_summary(run.summary);
  run.summary["status"] = "running";
  if (run.opt.resume) run.summary["resumed_from"] = resumed_from_json(*run.opt.resume, m.world().clock);
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
    std::fprintf(stderr, "%s: failed while settling\n%s: error: %s\n", run.program(), run.program(), e.what());
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
    run.main = m.run(so);
    if (run.main.interrupted) run.outcome.interrupt(stop_signal() != 0 ? stop_signal() : SIGTERM);
  });
  if (run.outcome.failed()) {  // a stage that threw: the steps it took, and its wall time
    run.main.steps = world.clock.step - first;
    run.main.wall_seconds = seconds_since(run0);
  }
  run.outcome.steps = run.main.steps;
  run.outcome.wall = run.main.wall_seconds;
}

// The checkpoint at the end, the outputs closed, the final state's analyses.
void end_outputs(Run& run) {
  Model& m = run.model;
  if (m.checkpoint_at_end()) run.guard([&] { run.outcome.checkpoint_file = m.write_checkpoint().string(); });
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
  s["checkpoints_written"] = m.checkpoints_written();
  if (!run.outcome.checkpoint_file.empty()) s["checkpoint"] = run.outcome.checkpoint_file;
  summary_counts_at_end(s, m.counts());
  const std::vector<Schedule*> steps = m.schedules();
  std::vector<const Schedule*> timed(steps.begin(), steps.end());
  timed.push_back(&run.observers);
  s["time_per_system"] = timings_json(timed);
  m.close_summary(s, main);
}

// The final files and summary.json; a write that fails leaves the earlier ones as they were.
void write_end(Run& run) {
  try {
    run.model.write_final_files(run.out);
    write_summary_json(run.out / "summary.json", run.summary);
  } catch (const WriteError& e) {
    RunOutcome& r = run.outcome;
    if (r.failure.empty()) r.fail(e.what() + write_failure_fix(run.place.command(), run.opt, run.out, run.go_on_from()));
    else r.fail_also(e.what());
  }
}

void say_end(Run& run) {
  say_done(run.place.program, run.outcome, run.model.world().clock.t, run.model.rate(run.summary));
  if (!run.outcome.failure.empty()) return;
  if (const std::string words = run.model.last_words(); !words.empty())
    std::fprintf(stderr, "%s: %s\n", run.program(), words.c_str());
  const std::filesystem::path from = run.go_on_from();
  if (run.outcome.status == "interrupted" && !from.empty())
    std::fprintf(stderr, "%s: stopped by a signal at step %lld; go on with: %s %s --out %s --resume %s\n",
                 run.program(), static_cast<long long>(run.model.world().clock.step), run.place.command().c_str(),
                 run.opt.scene.string().c_str(), run.out.string().c_str(), from.string().c_str());
}

}  // namespace

int run_model(Model& model, const CliOptions& opt, const RunPlace& place) {
  Run run(model, opt, place);
  const bool ends = place.writer || place.every_process_ends;  // this process takes part in the end
  together(place, [&] { open_run(run); });
  RunCounts at_start;
  if (ends) at_start = model.counts();  // collective on ranks
  together(place, [&] {
    if (place.writer) open_summary(run, at_start);
  });
  if (!settle_stage(run)) return 3;
  for (Schedule* s : model.schedules()) s->reset_timings();
  together(place, [&] {
    if (ends) model.observe(run.observers, run.out, run.from.get());
  });
  main_stage(run);
  if (!ends) return run.outcome.rc;  // the others' failures are the writer's to report
  end_outputs(run);
  close_summary(run);
  if (!place.writer) return run.outcome.rc;
  write_end(run);
  say_end(run);
  return run.outcome.rc;
}

}  // namespace gf
