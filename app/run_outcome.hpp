// How a run's main stage ends, recorded and reported the same way by every model: the status
// ("completed", "interrupted" or "failed" with its message), the checkpoint written at the end, the
// exit status (3 for a failure, 128 + the signal for a stop), the steps and wall time of this run; and the lines every run prints
// as it resumes and as it ends.
#pragma once

#include <chrono>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "engine/atomic_file.hpp"
#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"

namespace gf {

struct RunOutcome {
  std::string status = "completed";
  std::string failure;
  std::string checkpoint_file;  // the checkpoint written at the end, if one was
  int rc = 0;
  std::int64_t steps = 0;  // this run's main-stage steps, also when one failed
  double wall = 0;         // s, this run's stepping

  bool failed() const { return status == "failed"; }
  void fail(std::string why) {
    status = "failed";
    failure = std::move(why);
    rc = 3;
  }
  // Stopped by `signal` after the step in flight, its results kept: the shell's status of a process
  // stopped by that signal (130 for SIGINT, 143 for SIGTERM), so scripts and `timeout` see the stop.
  void interrupt(int signal) {
    status = "interrupted";
    rc = 128 + signal;
  }
  // A write after an earlier failure: the first message stays, this one follows it.
  void fail_also(const std::string& why) { fail(failure.empty() ? why : failure + "; then " + why); }
};

// Runs `body` unless the run has failed already, recording what it throws: a write that failed (a full
// disk, a file-size limit) with how to go on (resume from the run's checkpoint when have_checkpoint()
// says it has one, else run again), anything else with its message.
template <class Body, class HaveCheckpoint>
void guarded(RunOutcome& r, const CliOptions& opt, const std::filesystem::path& out, HaveCheckpoint&& have_checkpoint,
             Body&& body) {
  if (r.failed()) return;
  try {
    body();
  } catch (const WriteError& e) {
    r.fail(e.what() + write_failure_fix(opt, out, have_checkpoint()));
  } catch (const std::exception& e) {
    r.fail(e.what());
  }
}

// "PROGRAM: resuming from FILE at step N (t = T s)NOTE", and the summary's "resumed_from".
void say_resuming(std::string_view program, const std::filesystem::path& file, const Clock& clock,
                  const std::string& note);
nlohmann::json resumed_from_json(const std::filesystem::path& file, const Clock& clock);

// A sampled row as JSON by column name, null where a value is not finite.
nlohmann::json row_json(const std::vector<std::string>& columns, const std::vector<double>& row);

// "PROGRAM: STATUS after N steps (T s simulated) in W s wall: RATE", then the failure if any.
void say_done(std::string_view program, const RunOutcome& r, double simulated, const std::string& rate);

double seconds_since(std::chrono::steady_clock::time_point t0);

}  // namespace gf
