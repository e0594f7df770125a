// grainflow_mpi: a DEM scene stepped on several ranks (RankSimulation), launched by mpiexec.
//
//   mpiexec -n P grainflow_mpi run SCENE [--out DIR] [--steps N] [--threads T] [--set key=value]...
//                                  [--resume DIR/checkpoints/checkpoint_ranks.gfc] [--rebalance RATIO]
//
// (or mpiexec -n P grainflow run ..., which hands over to this program: app/rank_launch.hpp). The
// command line is grainflow's, parsed by the same code (app/cli.hpp): the same options, checks and
// messages; `grainflow_mpi check SCENE` checks on rank 0 as `grainflow check` does.
//
// Runs the scene's settling stage, then its main stage (or up to step N of it). Into DIR, as
// `grainflow run` on one rank: series.csv (rank 0, at output.series_interval), VTK frames at
// output.frame_interval (one .vtp piece per rank, a .pvtp per frame and frames.pvd; rank_frames.hpp),
// checkpoints at output.checkpoint_interval and at the end (output.checkpoint_at_end; one part per
// rank and an index, rank_checkpoints.hpp), final_state.csv (gathered to rank 0) and summary.json
// from rank 0: the grains, steps and wall time (outputs included), the particle-steps per second of
// rank 0's own grains and of all ranks together, the decomposition's counters over the main stage
// (rebuilds, rows migrated, ghost rows at the end), the final kinetic energy and momentum and the
// last series row. SIGINT/SIGTERM stop the main stage after the same step on every rank, with the
// checkpoint written and the summary "interrupted". --resume continues a checkpoint's run on as many ranks bit for bit (no settling;
// series.csv and the frames go on from the checkpoint, rows and frames the stopped run wrote after it
// are replaced); on another number of ranks (one included) it continues to round-off, the rows and
// springs shared out to the new boxes (RankSimulation::restore_portable), and the parts it read are
// left on disk. Exit status 2 for a scene, usage or checkpoint error (every rank stops; rank 0 names
// the file), 3 when the run became unphysical (every rank is stopped by MPI_Abort) or an output could
// not be written (every rank stops and finalises; rank 0 names the file).
//
// A scene of composite bodies ([[bodies]]) runs differently (app/mpi/rank_body_app.hpp):
// every rank steps the whole scene with the member contacts shared out, bit-identical to `grainflow
// run`, whose outputs rank 0 writes; --resume takes DIR/checkpoints/checkpoint.gfc on any rank count,
// and --rebalance does not apply.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>
#include <tbb/info.h>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/run_outcome.hpp"
#include "app/run_summary.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "engine/run_loop.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/output/mpi/rank_checkpoint_index.hpp"
#include "systems/setup/mpi/rank_checkpoints.hpp"
#include "systems/setup/mpi/rank_outputs.hpp"
#include "systems/output/summary_json.hpp"
#include "app/mpi/rank_body_app.hpp"

namespace {

using gf::seconds_since;

// The main stage's steps with the outputs, then the checkpoints, observing the start and every step
// after it.
// Returns whether a rank was asked to stop (SIGINT or SIGTERM): every rank then ends after the same
// step, since each step's check is a collective maximum over the ranks.
bool run_main_stage(gf::RankSimulation& sim, gf::RankOutputs& outputs, gf::RankCheckpoints& checkpoints,
                    std::int64_t steps) {
  const gf::MpiContext& mpi = sim.mpi();
  outputs.observe(sim.world());
  checkpoints.observe(sim, outputs);
  for (std::int64_t k = 0; k < steps; ++k) {
    if (mpi.max(gf::stop_requested() ? 1.0 : 0.0) > 0.0) return true;
    sim.advance(1);
    outputs.observe(sim.world());
    checkpoints.observe(sim, outputs);
  }
  return false;
}

// A checkpoint's state on every rank: each rank's part opened and restored. Collective; a
// RankFailure on every rank when any part cannot be (rank 0's message names the files).
struct Resumed {
  std::unique_ptr<gf::CheckpointReader> part;  // this rank's, or part 0 when the rank count differs
  gf::RankOutputRows rows;
  int other_ranks = 0;  // the rank count that wrote the checkpoint, when it differs from this run's
};

Resumed resume(const std::filesystem::path& index, gf::RankSimulation& sim, const gf::MpiContext& mpi) {
  Resumed r;
  gf::RankCheckpointIndex idx;
  gf::on_every_rank(mpi, [&] { idx = gf::read_rank_index(index); });
  if (idx.ranks == mpi.size()) {
    r.part = gf::open_rank_part(index, mpi);
    gf::on_every_rank(mpi, [&] { sim.restore(*r.part); });
  } else {
    // Another rank count: part 0 gives every rank the clock and the outputs' state, and the parts
    // are shared out among the ranks to be read (RankSimulation::restore_portable).
    gf::on_every_rank(mpi, [&] { r.part = std::make_unique<gf::CheckpointReader>(index.parent_path() / idx.parts[0]); });
    std::vector<std::filesystem::path> mine;
    for (std::size_t k = static_cast<std::size_t>(mpi.rank()); k < idx.parts.size(); k += static_cast<std::size_t>(mpi.size()))
      mine.push_back(index.parent_path() / idx.parts[k]);
    sim.restore_portable(*r.part, mine);
    r.other_ranks = idx.ranks;
  }
  gf::on_every_rank(mpi, [&] { r.rows = gf::RankOutputs::written_rows(*r.part); });
  return r;
}

// The outputs and checkpoints take their state back from the part. Collective (RankFailure).
void resume_outputs(const Resumed& r, const std::filesystem::path& index, gf::RankOutputs& outputs,
                    gf::RankCheckpoints& checkpoints, const gf::MpiContext& mpi) {
  outputs.restore(*r.part);
  // A set of parts of another rank count is not this run's to replace: the next set leaves it.
  gf::on_every_rank(mpi, [&] { checkpoints.restore(*r.part, r.other_ranks ? std::filesystem::path() : index); });
}

// A checkpoint that cannot be resumed: rank 0 says why (the message names the file and the fix).
int refuse_resume(const gf::RankFailure& e, const gf::MpiContext& mpi) {
  if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: error: cannot resume: %s\n", e.what());
  return 2;
}

// A file that could not be written: what rank 0 says and records, with the fix.
// With a checkpoint on disk (this run's, or the one it resumed), the run can go on from it.
std::string write_failure(const gf::RankFailure& e, const gf::CliOptions& o, int ranks, const std::filesystem::path& checkpoint) {
  const std::string then = checkpoint.empty() ? "then run again"
                                              : "then resume: mpiexec -n " + std::to_string(ranks) +
                                                    " grainflow_mpi run " + o.scene.string() + " --out " +
                                                    o.out_dir().string() + " --resume " + checkpoint.string();
  return std::string(e.what()) + ". Fix: make sure the folder '" + o.out_dir().string() +
         "' is writable and its disk has room (or write less: output.frame_interval, output.series_interval, "
         "output.checkpoint_interval), " + then;
}

// From rank 0. A summary that cannot be written after a completed run stops every rank (the others
// may be past their last collective call); after a failed one, the failure is reported already.
void write_summary(const nlohmann::json& summary, const gf::CliOptions& opt, const gf::MpiContext& mpi, bool abort) {
  if (mpi.rank() != 0) return;
  try {
    std::filesystem::create_directories(opt.out_dir());
    gf::write_summary_json(opt.out_dir() / "summary.json", summary);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: %s\n", e.what());
    if (abort) MPI_Abort(mpi.comm(), 2);
  }
}

// A file that could not be written, on every rank: rank 0 records and reports, then all finalise.
int fail_write(const gf::RankFailure& e, const gf::CliOptions& opt, const gf::MpiContext& mpi, nlohmann::json& summary,
               const std::filesystem::path& checkpoint) {
  summary["status"] = "failed";
  summary["failure"] = write_failure(e, opt, mpi.size(), checkpoint);
  if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: error: %s\n", summary["failure"].get<std::string>().c_str());
  write_summary(summary, opt, mpi, false);
  return 3;
}


// A scene of composite bodies: every rank steps it, the contacts shared out (rank_body_app.hpp).
int run_bodies(const gf::CliOptions& opt, const gf::DemScene& scene, const gf::MpiContext& mpi) {
  try {
    return gf::run_rank_body_command(opt, scene, mpi);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), e.what());
    MPI_Abort(mpi.comm(), 2);
  }
  return 2;
}

// What the ranks measured over the main stage, for the summary.
struct MainStage {
  bool interrupted = false;
  std::int64_t settled = 0;
  double settle_wall = 0, wall = 0, mine = 0, own_steps = 0, all_steps = 0;
  gf::RankCounters before;
  std::int64_t kept = 0;  // neighbour lists kept past half the skin, every rank alike
};

MainStage step_main_stage(gf::RankSimulation& sim, gf::RankOutputs& outputs, gf::RankCheckpoints& checkpoints,
                          std::int64_t steps, bool resumed) {
  const gf::MpiContext& mpi = sim.mpi();
  MainStage m;
  const auto t_settle = std::chrono::steady_clock::now();
  m.settled = resumed ? 0 : sim.settle();
  m.settle_wall = mpi.max(seconds_since(t_settle));
  m.before = sim.counters();
  const auto& cover = sim.world().resources.get<gf::BroadphaseState>().cover;
  const std::int64_t kept_before = cover.kept;
  mpi.barrier();
  const auto t_run = std::chrono::steady_clock::now();
  m.interrupted = run_main_stage(sim, outputs, checkpoints, steps);
  if (sim.scene().output.checkpoint_at_end && !checkpoints.holds(sim.world().clock.step)) checkpoints.write(sim, outputs);
  m.mine = seconds_since(t_run);
  m.wall = mpi.max(m.mine);
  m.own_steps = sim.counters().particle_steps - m.before.particle_steps;
  m.all_steps = mpi.sum(m.own_steps);
  m.kept = cover.kept - kept_before;
  return m;
}

// The summary of a finished main stage (collective: the sums over the ranks).
void summarise(nlohmann::json& summary, const gf::CliOptions& opt, gf::RankSimulation& sim, const MainStage& m,
               const gf::RankOutputs& outputs, const gf::RankCheckpoints& checkpoints, const gf::SeriesRow& last,
               std::int64_t grains, std::int64_t first_step, int threads) {
  const gf::MpiContext& mpi = sim.mpi();
  const std::array<double, 3> p = sim.total_momentum();
  const double energy = sim.total_kinetic_energy();
  const std::int64_t still = sim.total_grains();
  const std::int64_t migrated = mpi.sum(sim.counters().migrated - m.before.migrated);
  const std::int64_t ghosts = mpi.sum(sim.counters().ghosts);
  if (checkpoints.written() > 0) summary["checkpoint"] = checkpoints.index_path().string();
  gf::summary_counts_at_end(summary, {still, 0});
  summary["status"] = m.interrupted ? "interrupted" : "completed";
  summary["threads_per_rank"] = threads;
  summary["grains"] = grains;
  summary["grains_at_end"] = still;
  summary["settle_steps"] = m.settled;
  summary["settle_wall_seconds"] = m.settle_wall;
  summary["steps"] = sim.world().clock.step;
  summary["steps_this_run"] = sim.world().clock.step - first_step;
  summary["wall_seconds"] = m.wall;
  summary["particle_steps_per_second"] = m.wall > 0 ? m.all_steps / m.wall : 0.0;
  summary["rank0_particle_steps_per_second"] = m.mine > 0 ? m.own_steps / m.mine : 0.0;
  summary["rank0_grains_at_end"] = static_cast<std::int64_t>(sim.grains().n_owned);
  summary["settle_neighbour_rebuilds"] = m.before.rebuilds;
  summary["neighbour_rebuilds"] = sim.counters().rebuilds - m.before.rebuilds;
  summary["neighbour_lists_kept"] = m.kept;
  summary["rows_migrated"] = migrated;
  summary["rebalances"] = sim.counters().rebalances - m.before.rebalances;
  summary["rebalance_ratio"] = opt.rebalance;
  summary["ghost_rows_at_end"] = ghosts;
  summary["kinetic_energy"] = energy;
  summary["momentum"] = {p[0], p[1], p[2]};
  summary["series_rows"] = outputs.series_rows();
  summary["frames"] = outputs.frames();
  summary["pictures"] = outputs.pictures();
  if (!outputs.last_picture().empty()) summary["last_picture"] = outputs.last_picture().string();
  summary["checkpoints_written"] = checkpoints.written();
  summary["final"] = gf::final_row_json(last);
  if (const gf::FlowState* f = sim.world().resources.find<gf::FlowState>())
    summary["flow"] = {{"grains", still},
                       {"holdup_mass", last.holdup_mass},
                       {"fed_grains", f->fed_grains()},
                       {"fed_mass", f->fed_mass()},
                       {"discharged", f->discharged()},
                       {"discharged_mass", f->discharged_mass()},
                       {"feed_backlog", f->backlog()}};
}

// Rank 0's last lines: the rate, the picture, and how to go on after a signal.
void say_done(const nlohmann::json& summary, const gf::CliOptions& opt, const gf::MpiContext& mpi) {
  if (mpi.rank() != 0) return;
  std::fprintf(stderr, "grainflow_mpi: %lld steps in %.2f s wall: %.3g particle-steps/s on all ranks, %.3g on rank 0\n",
               static_cast<long long>(summary["steps_this_run"].get<std::int64_t>()), summary["wall_seconds"].get<double>(),
               summary["particle_steps_per_second"].get<double>(), summary["rank0_particle_steps_per_second"].get<double>());
  if (summary.contains("last_picture"))
    std::fprintf(stderr, "grainflow_mpi: picture of the drum: %s\n", summary["last_picture"].get<std::string>().c_str());
  if (summary["status"] == "interrupted" && summary.contains("checkpoint"))
    std::fprintf(stderr, "grainflow_mpi: stopped by a signal at step %lld; go on with: mpiexec -n %d grainflow_mpi run %s --out %s --resume %s\n",
                 static_cast<long long>(summary["steps"].get<std::int64_t>()), mpi.size(), opt.scene.string().c_str(),
                 opt.out_dir().string().c_str(), summary["checkpoint"].get<std::string>().c_str());
}

void say_start(const gf::CliOptions& opt, gf::RankSimulation& sim, const Resumed& resumed, std::int64_t grains,
               std::int64_t steps, int threads) {
  if (sim.mpi().rank() != 0) return;
  const gf::Clock& start = sim.world().clock;
  std::fprintf(stderr, "grainflow_mpi: %s: %lld grains on %d ranks, %d threads each, %lld steps -> %s\n",
               opt.scene.string().c_str(), static_cast<long long>(grains), sim.mpi().size(), threads,
               static_cast<long long>(steps), opt.out_dir().string().c_str());
  if (opt.resume)
    std::fprintf(stderr, "grainflow_mpi: resuming from %s at step %lld (t = %.6g s)%s\n", opt.resume->string().c_str(),
                 static_cast<long long>(start.step), start.t,
                 resumed.other_ranks ? (", written on " + std::to_string(resumed.other_ranks) +
                                        " ranks: its rows and springs shared out to this run's boxes").c_str()
                                     : "");
}

// The outputs and checkpoints of the run, resumed where it was resumed; -1 on success, else the exit
// status.
int open_outputs(const gf::CliOptions& opt, gf::RankSimulation& sim, Resumed& resumed, nlohmann::json& summary,
                 std::unique_ptr<gf::RankOutputs>& outputs, std::unique_ptr<gf::RankCheckpoints>& checkpoints) {
  const gf::MpiContext& mpi = sim.mpi();
  const gf::DemScene& scene = sim.scene();
  try {
    std::optional<gf::RankOutputRows> rows;
    if (opt.resume) rows = resumed.rows;
    outputs = std::make_unique<gf::RankOutputs>(scene, opt.out_dir(), mpi, rows);
    checkpoints = std::make_unique<gf::RankCheckpoints>(
        gf::RankCheckpointSettings{opt.out_dir(), scene.output.checkpoint_interval, scene.output.checkpoint_keep_all},
        mpi);
  } catch (const gf::RankFailure& e) {
    return fail_write(e, opt, mpi, summary, opt.resume ? *opt.resume : std::filesystem::path());
  }
  if (opt.resume) {
    try {
      resume_outputs(resumed, *opt.resume, *outputs, *checkpoints, mpi);
    } catch (const gf::RankFailure& e) {
      return refuse_resume(e, mpi);
    }
  }
  resumed.part.reset();  // the part's bytes are not needed past here
  return -1;
}

// A scene of grains on the ranks: load (or resume), step, write, summarise. Returns the exit status.
int run_ranks(const gf::CliOptions& opt, const gf::MpiContext& mpi, int threads) {
  std::unique_ptr<gf::RankSimulation> sim;
  try {
    gf::DemScene scene = gf::RankSimulation::load_scene(opt.scene, opt.overrides);
    if (scene.bodies) return run_bodies(opt, scene, mpi);
    sim = std::make_unique<gf::RankSimulation>(std::move(scene), mpi);
    sim->set_rebalance(opt.rebalance);
  } catch (const std::exception& e) {
    // Every rank loads the same scene and fails alike: rank 0 reports.
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: %s\n", e.what());
    return 2;
  }
  Resumed resumed;
  if (opt.resume) {
    try {
      resumed = resume(*opt.resume, *sim, mpi);
    } catch (const gf::RankFailure& e) {
      return refuse_resume(e, mpi);
    }
  }
  const std::int64_t first_step = sim->world().clock.step;
  const std::int64_t grains = sim->total_grains();
  // --steps and the scene's duration count the whole main stage: a resumed run ends where the
  // uninterrupted one would.
  const std::int64_t total = opt.steps ? *opt.steps : sim->scene().main_steps();
  const std::int64_t steps = std::max<std::int64_t>(0, total - first_step);
  say_start(opt, *sim, resumed, grains, steps, threads);
  nlohmann::json summary;
  gf::summary_opening(summary, opt, "spheres", {grains, 0}, mpi.size(), static_cast<std::size_t>(threads));
  if (opt.resume)
    summary["resumed_from"] = {{"checkpoint", opt.resume->string()}, {"step", first_step}, {"time", sim->world().clock.t}};
  std::unique_ptr<gf::RankOutputs> outputs;
  std::unique_ptr<gf::RankCheckpoints> checkpoints;
  if (const int failed = open_outputs(opt, *sim, resumed, summary, outputs, checkpoints); failed >= 0) return failed;
  try {
    const MainStage m = step_main_stage(*sim, *outputs, *checkpoints, steps, opt.resume.has_value());
    const gf::SeriesRow& last = outputs->finish(sim->world());
    summarise(summary, opt, *sim, m, *outputs, *checkpoints, last, grains, first_step, threads);
  } catch (const gf::RankFailure& e) {
    const bool written = checkpoints->written() > 0;
    return fail_write(e, opt, mpi, summary,
                      written ? checkpoints->index_path() : opt.resume ? *opt.resume : std::filesystem::path());
  } catch (const gf::StabilityError& e) {
    std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), e.what());
    MPI_Abort(mpi.comm(), 3);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), e.what());
    MPI_Abort(mpi.comm(), 2);
  }
  write_summary(summary, opt, mpi, true);
  say_done(summary, opt, mpi);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  gf::MpiContext mpi(&argc, &argv);
  gf::install_stop_handlers();
  gf::CliOptions opt;
  try {
    opt = gf::parse_cli(argc, argv, "grainflow_mpi");
  } catch (const gf::CliError& e) {
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: %s\n%s", e.what(), gf::usage("grainflow_mpi").c_str());
    return 2;
  }
  if (opt.command == "help" || opt.command == "version") {
    if (mpi.rank() == 0)
      std::printf("%s", (opt.command == "help" ? gf::usage("grainflow_mpi") : gf::version_line("grainflow_mpi")).c_str());
    return 0;
  }
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  if (opt.command == "check") {  // one process checks; the others wait for its verdict
    int status = 0;
    if (mpi.rank() == 0) {
      try {
        status = gf::check_command(opt);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "grainflow_mpi: error: %s\n", e.what());
        status = 1;
      }
    }
    return static_cast<int>(mpi.max(static_cast<double>(status)));
  }
  return run_ranks(opt, mpi, threads);
}
