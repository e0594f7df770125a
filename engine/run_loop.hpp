// The stepping loop: triggers the step graph, advances the clock, runs the observers (outputs and
// analyses, which decide themselves whether they are due), and reports progress on stderr.
#pragma once

#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>

#include "engine/schedule.hpp"
#include "engine/world.hpp"

namespace gf {

// A run that became unphysical (non-finite state, overlaps past the limit, ...), thrown by any
// system or observer; the message says what broke, when, and what to change. The CLI turns it
// into exit status 3 with summary.json "failed".
class StabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct StageReport {
  std::int64_t steps = 0;     // steps completed in this stage
  double particle_steps = 0;  // rows stepped (StageOptions::rows) summed over those steps (rows change in continuous scenes)
  double wall_seconds = 0.0;  // s
  bool interrupted = false;   // stopped early by SIGINT/SIGTERM (results so far are on disk)
};

struct StageOptions {
  std::string label = "run";
  std::int64_t steps = 0;
  Schedule* observe = nullptr;   // run after every step and once before the first
  bool observe_start = true;      // false: not before the first (a resumed run whose start was observed)
  double progress_seconds = 2.0;  // wall seconds between progress lines; <= 0 for none
  // Rows the step advances (for particle-steps); unset: the grains owned.
  std::function<double(const World&)> rows;
};

// Runs `opt.steps` steps of every simulation kind (grains, liquid, both). The clock is
// t = t0 + step dt (advance_clock: no accumulated round-off).
StageReport run_stage(World& world, Schedule& step, const StageOptions& opt);

// SIGINT/SIGTERM stop the stage after the step in flight, so a killed run still closes its files
// and writes its summary; SIGXFSZ is ignored, so a file-size limit fails a write (WriteError)
// instead of killing the process. Installed once by the CLI.
void install_stop_handlers();
bool stop_requested();
// The signal that asked the run to stop (SIGINT, SIGTERM); 0 when none did.
int stop_signal();

// Processes that step one state together (grainflow_mpi's body scenes) must stop after the same
// step. With an agreement installed, run_stage asks it before every step whether any process wants
// to stop (`any(mine)`, a collective call on every process): for a signal, or for an observer that
// failed on this process, whose exception is then held until every process has stopped and
// rethrown. Installed once by such a program; an empty function removes it.
void install_stop_agreement(std::function<bool(bool)> any);

}  // namespace gf
