// `grainflow run` and `grainflow check` for MPS liquid scenes, with the DEM side's conventions: series.csv
// flushed per row, VTK frames with a .pvd index, summary.json rewritten atomically at start and end, exit code 3
// and status "failed" when a stability detector stops the run.
#include <stdexcept>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include "engine/atomic_file.hpp"
#include "engine/cli.hpp"
#include "engine/run_loop.hpp"
#include "systems/mps/liquid_observables.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/output/vtk_frames.hpp"
#include "systems/setup/app.hpp"

namespace gf {

namespace {

std::size_t threads_in_use() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

const char* geometry_name(LiquidGeometry::Kind k) {
  switch (k) {
    case LiquidGeometry::Kind::Box: return "box";
    case LiquidGeometry::Kind::Tank: return "tank";
    case LiquidGeometry::Kind::Channel: return "channel";
    case LiquidGeometry::Kind::Pipe: return "pipe";
  }
  return "?";
}

// Frames reuse the DEM frame writer: nodes as points of radius l0/2, "type" = kind + 1 (1 fluid, 2 wall, 3 dummy).
void to_grains(const FluidNodes& f, double l0, Grains& g) {
  if (g.n != f.size()) g.resize(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) {
    g.pos.x[i] = f.x[i];
    g.pos.y[i] = f.y[i];
    g.pos.z[i] = f.z[i];
    g.vel.x[i] = f.u[i];
    g.vel.y[i] = f.v[i];
    g.vel.z[i] = f.w[i];
    g.radius.r[i] = 0.5 * l0;
    g.species.type[i] = f.kind[i];
    g.pid.id[i] = static_cast<std::int64_t>(i);
  }
}

}  // namespace

int check_liquid_command(const CliOptions& opt) {
  const LiquidScene s = load_liquid_scene(SceneDoc::load(opt.scene, opt.overrides));
  LiquidSimulation sim(s);
  FluidNodes& f = sim.nodes();
  const LiquidParams& p = s.params;
  std::printf("scene %s: valid\n", s.file.string().c_str());
  std::printf("model: MPS liquid (seed 003: Zhang kernel, Tanaka mixed source gamma = %g), %dD\n", p.gamma, p.k.dim);
  std::printf("geometry: %s; nodes: %zu fluid, %zu wall, %zu dummy\n", geometry_name(s.geometry.kind), f.count(kFluid),
              f.count(kWall), f.count(kDummy));
  std::printf("l0 = %g m, re = %g l0, n0 = %.6g, lambda = %.6g l0^2\n", p.k.l0, p.k.re / p.k.l0, p.k.n0,
              p.k.lambda / (p.k.l0 * p.k.l0));
  std::printf("systems per step (with the systems each waits for):\n%s", sim.step().describe().c_str());
  std::printf("PPE solver: %s, tolerance %g, max %d iterations\n",
              p.solver.kind == PpeSolverKind::MatrixFree ? "matrix-free Jacobi CG (TBB)" : "Eigen ConjugateGradient",
              p.solver.tolerance, p.solver.max_iterations);
  std::printf("dt = %g s: CFL %.3g (velocity scale %.3g m/s, limit %g), diffusion number %.3g (limit %g)%s\n", s.dt,
              s.cfl, s.velocity_scale, s.cfl_limit, s.diffusion, s.diffusion_limit,
              s.allow_unstable_dt && (s.cfl > s.cfl_limit || s.diffusion > s.diffusion_limit) ? " OVERRIDDEN" : "");
  std::printf("steps: %lld (%.4g s simulated)\n", static_cast<long long>(s.steps()), s.duration);
  return 0;
}

int run_liquid_command(const CliOptions& opt) {
  if (opt.resume)
    throw std::invalid_argument("--resume: liquid scenes have no checkpoints yet (" + opt.scene.string() +
                                "). Fix: run the liquid scene without --resume");
  const auto wall0 = std::chrono::steady_clock::now();
  const LiquidScene s = load_liquid_scene(SceneDoc::load(opt.scene, opt.overrides));
  const std::filesystem::path out = opt.out ? *opt.out : std::filesystem::path("runs") / opt.scene.stem();
  ensure_directory(out);
  LiquidSimulation sim(s);
  World& world = sim.world();
  FluidNodes& f = sim.nodes();
  const std::size_t n_fluid = f.count(kFluid);
  const std::size_t n_all = f.size();
  std::fprintf(stderr, "grainflow: %s: %zu fluid + %zu wall/dummy nodes, dt = %.3g s (CFL %.3g), %zu threads -> %s\n",
               s.file.string().c_str(), n_fluid, n_all - n_fluid, s.dt, s.cfl, threads_in_use(), out.string().c_str());

  nlohmann::json summary;
  summary["scene"] = s.file.string();
  summary["overrides"] = opt.overrides;
  summary["model"] = "mps";
  summary["fluid_nodes"] = n_fluid;
  summary["nodes"] = n_all;
  summary["threads"] = threads_in_use();
  summary["dt"] = s.dt;
  summary["l0"] = s.params.k.l0;
  summary["cfl_at_load"] = s.cfl;
  summary["diffusion_number"] = s.diffusion;
  summary["status"] = "running";
  write_summary_json(out / "summary.json", summary);

  std::unique_ptr<SeriesCsv> series;
  if (s.output.series_interval > 0) series = std::make_unique<SeriesCsv>(out / "series.csv", liquid_series_columns());
  std::unique_ptr<FrameSeries> frames;
  Grains scratch;
  if (s.output.frame_interval > 0) frames = std::make_unique<FrameSeries>(out);
  const std::int64_t series_every = s.output.series_interval > 0
                                        ? std::max<std::int64_t>(1, std::llround(s.output.series_interval / s.dt))
                                        : 0;
  const std::int64_t frame_every =
      s.output.frame_interval > 0 ? std::max<std::int64_t>(1, std::llround(s.output.frame_interval / s.dt)) : 0;
  auto observe = [&](std::int64_t k) {
    if (series && k % series_every == 0) {
      const auto row = sample_liquid(world, s);
      series->append(row);
    }
    if (frames && k % frame_every == 0) {
      to_grains(f, s.params.k.l0, scratch);
      frames->write(scratch, world.clock.t);
    }
  };

  const std::int64_t steps = opt.steps ? *opt.steps : s.steps();
  std::string status = "completed", failure;
  int rc = 0;
  std::int64_t done = 0;
  const auto run0 = std::chrono::steady_clock::now();
  auto last_print = run0;
  double ppe_iterations = 0;
  try {
    observe(0);
    for (std::int64_t k = 0; k < steps; ++k) {
      if (stop_requested()) {
        status = "interrupted";
        break;
      }
      sim.step_once();
      ++done;
      ppe_iterations += sim.diagnostics().ppe.iterations;
      observe(k + 1);
      const auto now = std::chrono::steady_clock::now();
      if (!opt.quiet && (std::chrono::duration<double>(now - last_print).count() >= 2.0 || k + 1 == steps)) {
        last_print = now;
        const double el = std::chrono::duration<double>(now - run0).count();
        const double sps = static_cast<double>(k + 1) / el;
        std::fprintf(stderr, "[run] t = %.6g s  step %lld/%lld  %.3g steps/s  %.3g particle-steps/s  ETA %.0f s\n",
                     world.clock.t, static_cast<long long>(k + 1), static_cast<long long>(steps), sps,
                     sps * static_cast<double>(n_fluid), static_cast<double>(steps - k - 1) / sps);
      }
    }
  } catch (const WriteError& e) {
    status = "failed";
    failure = std::string(e.what()) + ". Every file written before is complete. Fix: free space on the disk that "
              "holds '" + out.string() + "' (or write less: output.frame_interval, output.series_interval), then run again";
    rc = 3;
  } catch (const std::exception& e) {
    status = "failed";
    failure = e.what();
    rc = 3;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - run0).count();
  const auto last = sample_liquid(world, s);
  const auto cols = liquid_series_columns();
  nlohmann::json fin;
  for (std::size_t c = 0; c < cols.size(); ++c) fin[cols[c]] = std::isfinite(last[c]) ? nlohmann::json(last[c]) : nlohmann::json();
  summary["status"] = status;
  if (!failure.empty()) summary["failure"] = failure;
  summary["steps"] = done;
  summary["simulated_time"] = world.clock.t;
  summary["wall_seconds"] = wall;
  summary["total_wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  summary["steps_per_second"] = wall > 0 ? done / wall : 0.0;
  summary["particle_steps_per_second"] = wall > 0 ? static_cast<double>(done) * n_fluid / wall : 0.0;
  summary["mean_ppe_iterations"] = done > 0 ? ppe_iterations / done : 0.0;
  summary["frames"] = frames ? frames->count() : 0;
  summary["final"] = fin;
  nlohmann::json per = nlohmann::json::array();
  double total = 0;
  for (auto& t : sim.step().timings()) total += t.seconds;
  for (auto& t : sim.step().timings())
    per.push_back({{"system", t.name}, {"seconds", t.seconds}, {"calls", t.calls},
                   {"fraction", total > 0 ? t.seconds / total : 0.0}});
  summary["time_per_system"] = per;
  try {
    write_summary_json(out / "summary.json", summary);
  } catch (const WriteError& e) {
    // The earlier summary.json (status "running") stays as it was.
    failure += (failure.empty() ? "" : "; then ") + std::string(e.what());
    status = "failed";
    rc = 3;
  }
  std::fprintf(stderr, "grainflow: %s after %lld steps (%.4g s simulated) in %.1f s wall: %.3g particle-steps/s\n",
               status.c_str(), static_cast<long long>(done), world.clock.t, wall,
               wall > 0 ? static_cast<double>(done) * n_fluid / wall : 0.0);
  if (!failure.empty()) std::fprintf(stderr, "grainflow: error: %s\n", failure.c_str());
  return rc;
}

}  // namespace gf
