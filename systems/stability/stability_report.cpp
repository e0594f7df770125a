#include "systems/stability/stability_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "engine/run_loop.hpp"
#include "systems/contact/pair_contact.hpp"

namespace gf {

namespace {

std::string when(const StepContext& s) {
  char buf[160];
  if (s.prime)
    std::snprintf(buf, sizeof buf, "in the initial state (t = %.9g s)", s.t);
  else
    std::snprintf(buf, sizeof buf, "in step %lld of the %.*s stage (t = %.9g s to %.9g s)",
                  static_cast<long long>(s.step + 1), static_cast<int>(s.stage.size()), s.stage.data(), s.t,
                  s.t + s.dt);
  return buf;
}

std::string grain(const Grains& g, std::size_t row) {
  return "grain id " + std::to_string(g.pid.id[row]) + " (row " + std::to_string(row) + ")";
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

const char* const kFixStep =
    "Fix: reduce run.dt (`grainflow check` prints the critical step and its smallest term), or raise the "
    "stiffness";

// In the initial state no step has been taken: the input placed the grains so.
std::string fix(const StepContext& step) {
  return step.prime ? "Fix: place the grains apart (the state file's positions, or the fill's region and walls)"
                    : kFixStep;
}

}  // namespace

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
  throw StabilityError("the " + what + " of " + (bad ? grain(g, row) : std::string("a grain")) + " became non-finite " +
                       when(step) + ", in " + std::string(pass) + " (" + std::to_string(bad) +
                       " grains in all): the run blew up. " + kFixStep +
                       "; a state file with NaN or infinite values has the same effect");
}

void report_pair_overlap(const Grains& g, const PairForces& c, double limit, const StepContext& step) {
  double worst = -1.0;
  std::size_t at = 0, past = 0;
  for (std::size_t k = 0; k < c.contacts(); ++k) {
    const auto i = static_cast<std::size_t>(c.ci[k]), j = static_cast<std::size_t>(c.cj[k]);
    const double dx = g.pos.x[j] - g.pos.x[i], dy = g.pos.y[j] - g.pos.y[i], dz = g.pos.z[j] - g.pos.z[i];
    const double delta = g.radius.r[i] + g.radius.r[j] - std::sqrt(dx * dx + dy * dy + dz * dz);
    const double ratio = delta / (2.0 * std::min(g.radius.r[i], g.radius.r[j]));
    past += ratio > limit;
    if (ratio > worst) worst = ratio, at = k;
  }
  const auto i = static_cast<std::size_t>(c.ci[at]), j = static_cast<std::size_t>(c.cj[at]);
  throw StabilityError(grain(g, i) + " and " + grain(g, j) + " overlap by " + number(worst) +
                       " of the smaller diameter " + when(step) + ", past run.max_overlap = " + number(limit) + " (" +
                       std::to_string(past) + " contacts past it). " + fix(step) +
                       ", or raise run.max_overlap if such overlaps are intended");
}

void report_wall_overlap(const Grains& g, const Walls& walls, double limit, const StepContext& step) {
  double worst = -1.0;
  std::size_t at = 0, wall = 0, past = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    for (std::size_t w = 0; w < walls.list.size(); ++w) {
      Vec3d n;
      const double ratio =
          (g.radius.r[i] - wall_gap(walls.list[w], {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, n)) / (2.0 * g.radius.r[i]);
      past += ratio > limit;
      if (ratio > worst) worst = ratio, at = i, wall = w;
    }
  const std::string name = walls.list.empty() ? std::string("a wall") : "wall '" + walls.list[wall].name + "'";
  throw StabilityError(grain(g, at) + " overlaps " + name + " by " + number(worst) + " of its diameter " + when(step) +
                       ", past run.max_overlap = " + number(limit) + " (" + std::to_string(past) +
                       " wall contacts past it). " + fix(step) +
                       ", or raise run.max_overlap if such overlaps are intended");
}

}  // namespace gf
