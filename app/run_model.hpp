// One run skeleton for every model. `grainflow run` and `grainflow_mpi run` hand a Model to run_model,
// which does what every run does, the same way for spheres, composite bodies, liquid, liquid with
// grains and spheres on ranks:
//   the output folder; --resume (the model restores its state, then its observers theirs); the
//   opening line and summary.json's opening (status "running", written at once); the settling stage
//   (a StabilityError there is a failed run, exit 3); the observers; the main stage up to the
//   scene's end or --steps, stopped after the step in flight by SIGINT/SIGTERM; the checkpoint at
//   the end; the outputs closed; the analyses of the final state; summary.json's end (status,
//   steps, wall time, particle-steps/s, counts, the time per system with its fraction); the final
//   files; the last lines (with how to go on after a signal). Whatever a stage or a write throws is
//   recorded (run_outcome.hpp) and the files written before are kept.
// A model says only what is its own: what it steps, what its summary and opening line add, its
// observers and checkpoint contents, and what it writes at the end.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "app/run_summary.hpp"
#include "engine/checkpoint_file.hpp"
#include "engine/run_loop.hpp"
#include "engine/schedule.hpp"
#include "engine/world.hpp"

namespace gf {

class CheckpointOutput;

class Model {
 public:
  virtual ~Model() = default;

  // The scene as its systems read it (SceneDoc::resolved_json), for summary.json; empty: not recorded.
  std::string scene_json;

  // ---- What it is.
  virtual std::string_view kind() const = 0;  // summary.json "model": spheres, bodies, liquid, coupled
  virtual World& world() = 0;
  // Grains (or bodies) and liquid nodes now, over every process (collective on ranks).
  virtual RunCounts counts() = 0;
  // The schedules a step runs, for the time per system.
  virtual std::vector<Schedule*> schedules() = 0;

  // ---- The start.
  // Opens the checkpoint `file` and restores the state from it (restore); returns the reader the
  // observers take their state from.
  virtual std::unique_ptr<CheckpointReader> resume(const std::filesystem::path& file);
  virtual void restore(const CheckpointReader& from) = 0;
  virtual std::string resumed_note() const { return ""; }  // added to the line that says a run resumes
  // The opening line after the program's name: what is stepped, dt and the threads (the skeleton
  // adds the folder). Called on the process that writes only: no collective call.
  virtual std::string opening(std::size_t threads, int ranks) = 0;
  virtual std::string warning() const { return ""; }  // printed after the opening line when not empty
  virtual void open_summary(nlohmann::json& summary) = 0;  // the model's own keys
  // The settling stage before the main one, for a run that does not resume; a StabilityError fails the run.
  virtual StageReport settle(double progress_seconds) {
    (void)progress_seconds;
    return {};
  }
  // The main stage's observers, added to `observers` and built there, their state taken from `from`
  // when the run resumes (on the process that writes, or on every one that takes part in the end).
  virtual void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) = 0;

  // ---- The main stage.
  virtual std::int64_t last_step() const = 0;  // where the scene's main stage ends (--steps overrides)
  // Whether the observers see a resumed run's first state again (the run that wrote the checkpoint
  // saw it already; the grains' observers skip what they wrote).
  virtual bool observe_resumed_start() const { return true; }
  // Rows one step advances, for particle-steps/s: grains owned, moving bodies, liquid nodes.
  virtual double rows(const World& world) const = 0;
  // Runs the stage's steps (run_loop.hpp's run_stage: the observers after each, the stop on a signal).
  virtual StageReport run(const StageOptions& stage) = 0;

  // ---- Checkpoints.
  virtual bool checkpoint_at_end() const = 0;
  virtual std::filesystem::path write_checkpoint() = 0;  // one now; returns its file
  virtual std::size_t checkpoints_written() const = 0;
  // The file to resume from after a stop: this run's last checkpoint, else the one it resumed, else none.
  virtual std::filesystem::path go_on_from(const std::filesystem::path& out, const CheckpointReader* resumed) const;

  // ---- The end.
  virtual void finish_outputs() {}  // the outputs' last rows and indexes
  // After a main stage that did not fail: the analyses of the final state, into the summary.
  virtual void final_results(const std::filesystem::path& out, nlohmann::json& summary) {
    (void)out;
    (void)summary;
  }
  virtual void close_summary(nlohmann::json& summary, const StageReport& main) = 0;  // the model's own keys
  virtual void write_final_files(const std::filesystem::path& out) { (void)out; }
  // The rate the last line gives, from the closed summary.
  virtual std::string rate(const nlohmann::json& summary) const;
  virtual std::string last_words() const { return ""; }  // a line after the last one (the last picture)
};

// A model stepped by one schedule on one process (or alike on each), its checkpoints written by the
// CheckpointOutput among its observers, which observe() sets.
class ScheduledModel : public Model {
 public:
  virtual Schedule& step() = 0;
  std::vector<Schedule*> schedules() override { return {&step()}; }
  StageReport run(const StageOptions& stage) override { return run_stage(world(), step(), stage); }
  std::filesystem::path write_checkpoint() override;
  std::size_t checkpoints_written() const override;

 protected:
  CheckpointOutput* checkpoints_ = nullptr;
};

// Where a run steps: on one process (the default), or on several that step one state together, of
// which one writes and speaks. `together` runs a setup phase (which calls no collective) on this
// process and shares its outcome: a failure on any process throws on every one. With
// `every_process_ends`, every process takes part in the end (the checkpoint, the outputs closed, the
// summary's sums), which is collective; otherwise the others stop after the main stage.
struct RunPlace {
  bool writer = true;
  int ranks = 1;
  std::function<void(const std::function<void()>&)> together;
  bool every_process_ends = false;
  std::string program = "grainflow";
  // How the run is started again: "grainflow run", "mpiexec -n 4 grainflow_mpi run".
  std::string command() const;
};

// Runs `model` as `opt` asks; returns the exit status (0; 3 for a failed run).
int run_model(Model& model, const CliOptions& opt, const RunPlace& place = {});

}  // namespace gf
