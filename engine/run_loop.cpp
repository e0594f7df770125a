#include "engine/run_loop.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <exception>
#include <utility>

namespace gf {

namespace {
std::atomic<int> g_stop{0};  // the signal that asked the run to stop; 0: none
extern "C" void on_stop_signal(int sig) { g_stop.store(sig); }
std::function<bool(bool)> g_agree;

std::string human_seconds(double s) {
  char buf[64];
  if (s < 90)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 5400)
    std::snprintf(buf, sizeof buf, "%.1f min", s / 60);
  else
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  return buf;
}
// Whether an observer will read the state at the end of the step about to run: asked with the
// context the observers will be given then.
bool observed_after(const World& world, const StageOptions& opt) {
  if (!opt.observe) return false;
  Clock after = world.clock;
  advance_clock(after);
  StepContext c = next_step(after);
  c.stage = opt.label;
  return opt.observe->samples(world, c);
}
}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  // Past a file-size limit the default is to kill the process mid-write; ignored, the write fails
  // with EFBIG and the run stops with a message, its files whole.
  std::signal(SIGXFSZ, SIG_IGN);
}
bool stop_requested() { return g_stop.load() != 0; }
int stop_signal() { return g_stop.load(); }
void install_stop_agreement(std::function<bool(bool)> any) { g_agree = std::move(any); }

StageReport run_stage(World& world, Schedule& step, const StageOptions& opt) {
  using clock = std::chrono::steady_clock;
  StageReport rep;
  const auto t0 = clock::now();
  auto last_print = t0;
  if (world.clock.step == 0) world.clock.t0 = world.clock.t;
  const auto rows = [&] { return opt.rows ? opt.rows(world) : static_cast<double>(world.grains.n_owned); };
  auto context = [&] {
    StepContext c = next_step(world.clock);
    c.stage = opt.label;
    return c;
  };
  // Under an agreement an observer's failure is held until every process has stopped.
  std::exception_ptr held;
  auto observe = [&] {
    if (!opt.observe) return;
    if (!g_agree) return opt.observe->run_step(context());
    try {
      opt.observe->run_step(context());
    } catch (...) {
      held = std::current_exception();
    }
  };
  if (opt.observe_start) observe();
  for (std::int64_t k = 0; k < opt.steps; ++k) {
    const bool mine = stop_requested() || held;
    if (g_agree ? g_agree(mine) : mine) {
      rep.interrupted = true;
      break;
    }
    StepContext ctx = context();
    ctx.observed = k + 1 == opt.steps || observed_after(world, opt);
    step.run_step(ctx);
    advance_clock(world.clock);
    observe();
    ++rep.steps;
    rep.particle_steps += rows();
    if (opt.progress_seconds > 0) {
      const auto now = clock::now();
      if (std::chrono::duration<double>(now - last_print).count() >= opt.progress_seconds || k + 1 == opt.steps) {
        last_print = now;
        const double el = std::chrono::duration<double>(now - t0).count();
        const double sps = static_cast<double>(k + 1) / el;
        const double eta = static_cast<double>(opt.steps - k - 1) / sps;
        std::fprintf(stderr, "[%s] t = %.6g s  step %lld/%lld (%.1f%%)  %.3g steps/s  %.3g particle-steps/s  ETA %s\n",
                     opt.label.c_str(), world.clock.t, static_cast<long long>(k + 1),
                     static_cast<long long>(opt.steps), 100.0 * static_cast<double>(k + 1) / opt.steps, sps,
                     sps * rows(), human_seconds(eta).c_str());
      }
    }
  }
  step.complete(world);  // a stage stopped early (a signal, an observer's failure) ends whole too
  rep.wall_seconds = std::chrono::duration<double>(clock::now() - t0).count();
  if (held) std::rethrow_exception(held);
  return rep;
}

}  // namespace gf
