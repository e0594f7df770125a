#include "systems/stability/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/run_loop.hpp"

namespace gf {

namespace {

const char* const kFixStep =
    "Fix: reduce run.dt (`grainflow check` prints the critical step and its smallest term), or raise the "
    "stiffness";

}  // namespace

std::string step_words(const StepContext& s) {
  char buf[160];
  if (s.prime)
    std::snprintf(buf, sizeof buf, "in the initial state (t = %.9g s)", s.t);
  else
    std::snprintf(buf, sizeof buf, "in step %lld of the %.*s stage (t = %.9g s to %.9g s)",
                  static_cast<long long>(s.step + 1), static_cast<int>(s.stage.size()), s.stage.data(), s.t,
                  s.t + s.dt);
  return buf;
}

std::string grain_words(const Grains& g, std::size_t row) {
  return "grain id " + std::to_string(g.pid.id[row]) + " (row " + std::to_string(row) + ")";
}

// In the initial state no step has been taken: the input placed the grains so.
std::string overlap_fix(const StepContext& step) {
  return step.prime ? "Fix: place the grains apart (the state file's positions, or the fill's region and walls)"
                    : kFixStep;
}

void report_nonfinite(const Grains& g, const StepContext& step, std::string_view pass) {
  std::string what = "a value";
  std::size_t row = 0, bad = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double p[3] = {g.pos.x[i], g.pos.y[i], g.pos.z[i]};
    const double v[3] = {g.vel.x[i], g.vel.y[i], g.vel.z[i]};
    const double w[3] = {g.spin ? g.omega.x[i] : 0.0, g.spin ? g.omega.y[i] : 0.0, g.spin ? g.omega.z[i] : 0.0};
    const char* name = nullptr;
    for (int k = 0; k < 3 && !name; ++k) {
      if (!std::isfinite(p[k])) name = "position";
      else if (!std::isfinite(v[k])) name = "velocity";
      else if (!std::isfinite(w[k])) name = "angular velocity";
    }
    if (!name) continue;
    if (bad++ == 0) {
      row = i;
      what = name;
    }
  }
  throw StabilityError("the " + what + " of " + (bad ? grain_words(g, row) : std::string("a grain")) + " became non-finite " +
                       step_words(step) + ", in " + std::string(pass) + " (" + std::to_string(bad) +
                       " grains in all): the run blew up. " + kFixStep +
                       "; a state file with NaN or infinite values has the same effect");
}

}  // namespace gf
