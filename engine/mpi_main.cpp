// grainflow_mpi: a DEM scene stepped on several ranks (RankSimulation), launched by mpiexec.
//
//   mpiexec -n P grainflow_mpi run SCENE [--out DIR] [--steps N] [--threads T] [--set key=value]...
//                                  [--resume DIR/checkpoints/checkpoint_ranks.gfc] [--rebalance RATIO]
//
// (or mpiexec -n P grainflow run ..., which hands over to this program: engine/rank_launch.hpp; DIR
// defaults to runs/<scene name> as there, and grainflow's --quiet is accepted.)
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
// A scene of composite bodies ([[bodies]]) runs differently (systems/setup/mpi/rank_body_app.hpp):
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

#include "engine/mpi/mpi_context.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "engine/run_loop.hpp"
#include "systems/decomposition/mpi/rank_simulation.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/output/mpi/rank_checkpoint_index.hpp"
#include "systems/output/mpi/rank_checkpoints.hpp"
#include "systems/output/mpi/rank_outputs.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/setup/mpi/rank_body_app.hpp"

namespace {

struct Options {
  std::filesystem::path scene, out;
  std::int64_t steps = -1;
  int threads = 0;
  std::vector<std::string> overrides;
  std::optional<std::filesystem::path> resume;
  double rebalance = 1.25;  // the boxes are cut again past this ratio of most to mean cost; 0: never
  bool quiet = false;
};

const char* kUsage =
    "usage: mpiexec -n P grainflow_mpi run SCENE [--out DIR] [--steps N] [--threads T] [--set key=value]...\n"
    "                                   [--resume DIR/checkpoints/checkpoint_ranks.gfc] [--rebalance RATIO]\n"
    "  --rebalance RATIO  cut the ranks' boxes again at a neighbour rebuild where the costliest rank's grains\n"
    "                     cost more than RATIO times the mean (a grain costs 1 plus 0.46 for each neighbour\n"
    "                     pair it is in; default 1.25; 0: never)\n";

bool parse(int argc, char** argv, Options& o) {
  if (argc < 3 || std::string(argv[1]) != "run") return false;
  o.scene = argv[2];
  for (int k = 3; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--quiet") {  // grainflow's flag: progress lines (body scenes' rank 0 prints them) off
      o.quiet = true;
      continue;
    }
    if (k + 1 >= argc) return false;
    const std::string v = argv[++k];
    if (a == "--out") o.out = v;
    else if (a == "--steps") o.steps = std::stoll(v);
    else if (a == "--threads") o.threads = std::stoi(v);
    else if (a == "--set") o.overrides.push_back(v);
    else if (a == "--resume") o.resume = v;
    else if (a == "--rebalance") o.rebalance = std::stod(v);
    else return false;
  }
  if (o.out.empty()) o.out = std::filesystem::path("runs") / o.scene.stem();  // as grainflow run
  return true;
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

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
std::string write_failure(const gf::RankFailure& e, const Options& o, int ranks, const std::filesystem::path& checkpoint) {
  const std::string then = checkpoint.empty() ? "then run again"
                                              : "then resume: mpiexec -n " + std::to_string(ranks) +
                                                    " grainflow_mpi run " + o.scene.string() + " --out " +
                                                    o.out.string() + " --resume " + checkpoint.string();
  return std::string(e.what()) + ". Fix: make sure the folder '" + o.out.string() +
         "' is writable and its disk has room (or write less: output.frame_interval, output.series_interval, "
         "output.checkpoint_interval), " + then;
}

// From rank 0. A summary that cannot be written after a completed run stops every rank (the others
// may be past their last collective call); after a failed one, the failure is reported already.
void write_summary(const nlohmann::json& summary, const Options& opt, const gf::MpiContext& mpi, bool abort) {
  if (mpi.rank() != 0) return;
  try {
    std::filesystem::create_directories(opt.out);
    gf::write_summary_json(opt.out / "summary.json", summary);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: %s\n", e.what());
    if (abort) MPI_Abort(mpi.comm(), 2);
  }
}

// A file that could not be written, on every rank: rank 0 records and reports, then all finalise.
int fail_write(const gf::RankFailure& e, const Options& opt, const gf::MpiContext& mpi, nlohmann::json& summary,
               const std::filesystem::path& checkpoint) {
  summary["status"] = "failed";
  summary["failure"] = write_failure(e, opt, mpi.size(), checkpoint);
  if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: error: %s\n", summary["failure"].get<std::string>().c_str());
  write_summary(summary, opt, mpi, false);
  return 3;
}

// A scene of composite bodies: every rank steps it, the contacts shared out (rank_body_app.hpp).
int run_bodies(const Options& o, const gf::DemScene& scene, const gf::MpiContext& mpi) {
  gf::CliOptions c;
  c.command = "run";
  c.scene = o.scene;
  c.out = o.out;
  c.threads = o.threads;
  if (o.steps >= 0) c.steps = o.steps;
  c.overrides = o.overrides;
  c.quiet = o.quiet;
  c.resume = o.resume;
  try {
    return gf::run_rank_body_command(c, scene, mpi);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), e.what());
    MPI_Abort(mpi.comm(), 2);
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  gf::MpiContext mpi(&argc, &argv);
  gf::install_stop_handlers();
  Options opt;
  try {
    if (!parse(argc, argv, opt)) {
      if (mpi.rank() == 0) std::fputs(kUsage, stderr);
      return 2;
    }
  } catch (const std::exception&) {
    if (mpi.rank() == 0) std::fputs(kUsage, stderr);
    return 2;
  }
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));

  std::unique_ptr<gf::RankSimulation> sim;
  try {
    gf::DemScene scene = gf::RankSimulation::load_scene(opt.scene, opt.overrides);
    if (scene.bodies) return run_bodies(opt, scene, mpi);
    sim = std::make_unique<gf::RankSimulation>(std::move(scene), mpi);
  } catch (const std::exception& e) {
    // Every rank loads the same scene and fails alike: rank 0 reports.
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: %s\n", e.what());
    return 2;
  }
  try {
    sim->set_rebalance(opt.rebalance);
  } catch (const std::exception& e) {
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: --rebalance %g: %s\n%s", opt.rebalance, e.what(), kUsage);
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
  const gf::Clock start = sim->world().clock;
  const std::int64_t grains = sim->total_grains();
  // --steps and the scene's duration count the whole main stage: a resumed run ends where the
  // uninterrupted one would.
  const std::int64_t total = opt.steps >= 0 ? opt.steps : sim->scene().main_steps();
  const std::int64_t steps = std::max<std::int64_t>(0, total - start.step);
  if (mpi.rank() == 0) {
    std::fprintf(stderr, "grainflow_mpi: %s: %lld grains on %d ranks, %d threads each, %lld steps -> %s\n",
                 opt.scene.string().c_str(), static_cast<long long>(grains), mpi.size(), threads,
                 static_cast<long long>(steps), opt.out.string().c_str());
    if (opt.resume)
      std::fprintf(stderr, "grainflow_mpi: resuming from %s at step %lld (t = %.6g s)%s\n", opt.resume->string().c_str(),
                   static_cast<long long>(start.step), start.t,
                   resumed.other_ranks ? (", written on " + std::to_string(resumed.other_ranks) +
                                          " ranks: its rows and springs shared out to this run's boxes").c_str()
                                       : "");
  }
  const gf::DemScene& scene = sim->scene();
  nlohmann::json summary;
  if (opt.resume)
    summary["resumed_from"] = {{"checkpoint", opt.resume->string()}, {"step", start.step}, {"time", start.t}};
  std::unique_ptr<gf::RankOutputs> outputs;
  std::unique_ptr<gf::RankCheckpoints> checkpoints;
  try {
    std::optional<gf::RankOutputRows> rows;
    if (opt.resume) rows = resumed.rows;
    outputs = std::make_unique<gf::RankOutputs>(scene, opt.out, mpi, rows);
    checkpoints = std::make_unique<gf::RankCheckpoints>(
        gf::RankCheckpointSettings{opt.out, scene.output.checkpoint_interval, scene.output.checkpoint_keep_all}, mpi);
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
  try {
    const auto t_settle = std::chrono::steady_clock::now();
    const std::int64_t settled = opt.resume ? 0 : sim->settle();
    const double settle_wall = mpi.max(seconds_since(t_settle));
    const gf::RankCounters before = sim->counters();
    const auto& cover = sim->world().resources.get<gf::BroadphaseState>().cover;
    const std::int64_t kept_before = cover.kept;
    mpi.barrier();
    const auto t_run = std::chrono::steady_clock::now();
    const bool interrupted = run_main_stage(*sim, *outputs, *checkpoints, steps);
    if (scene.output.checkpoint_at_end && !checkpoints->holds(sim->world().clock.step)) checkpoints->write(*sim, *outputs);
    if (checkpoints->written() > 0) summary["checkpoint"] = checkpoints->index_path().string();
    const gf::SeriesRow& last = outputs->finish(sim->world());
    const double mine = seconds_since(t_run);
    const double wall = mpi.max(mine);
    const double own_steps = sim->counters().particle_steps - before.particle_steps;
    const double all_steps = mpi.sum(own_steps);
    const double energy = sim->total_kinetic_energy();
    const std::array<double, 3> p = sim->total_momentum();
    const std::int64_t still = sim->total_grains();
    const std::int64_t migrated = mpi.sum(sim->counters().migrated - before.migrated);
    const std::int64_t ghosts = mpi.sum(sim->counters().ghosts);
    summary["status"] = interrupted ? "interrupted" : "completed";
    summary["scene"] = opt.scene.string();
    summary["overrides"] = opt.overrides;
    summary["ranks"] = mpi.size();
    summary["threads_per_rank"] = threads;
    summary["grains"] = grains;
    summary["grains_at_end"] = still;
    summary["settle_steps"] = settled;
    summary["settle_wall_seconds"] = settle_wall;
    summary["steps"] = sim->world().clock.step;
    summary["steps_this_run"] = sim->world().clock.step - start.step;
    summary["wall_seconds"] = wall;
    summary["particle_steps_per_second"] = wall > 0 ? all_steps / wall : 0.0;
    summary["rank0_particle_steps_per_second"] = mine > 0 ? own_steps / mine : 0.0;
    summary["rank0_grains_at_end"] = static_cast<std::int64_t>(sim->grains().n_owned);
    summary["settle_neighbour_rebuilds"] = before.rebuilds;
    summary["neighbour_rebuilds"] = sim->counters().rebuilds - before.rebuilds;
    summary["neighbour_lists_kept"] = cover.kept - kept_before;  // past half the skin, every rank alike
    summary["rows_migrated"] = migrated;
    summary["rebalances"] = sim->counters().rebalances - before.rebalances;
    summary["rebalance_ratio"] = opt.rebalance;
    summary["ghost_rows_at_end"] = ghosts;
    summary["kinetic_energy"] = energy;
    summary["momentum"] = {p[0], p[1], p[2]};
    summary["series_rows"] = outputs->series_rows();
    summary["frames"] = outputs->frames();
    summary["pictures"] = outputs->pictures();
    if (!outputs->last_picture().empty()) summary["last_picture"] = outputs->last_picture().string();
    summary["checkpoints_written"] = checkpoints->written();
    summary["final"] = gf::final_row_json(last);
    if (const gf::FlowState* f = sim->world().resources.find<gf::FlowState>())
      summary["flow"] = {{"grains", still},
                         {"holdup_mass", last.holdup_mass},
                         {"fed_grains", f->fed_grains()},
                         {"fed_mass", f->fed_mass()},
                         {"discharged", f->discharged()},
                         {"discharged_mass", f->discharged_mass()},
                         {"feed_backlog", f->backlog()}};
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
  if (mpi.rank() == 0) {
    std::fprintf(stderr, "grainflow_mpi: %lld steps in %.2f s wall: %.3g particle-steps/s on all ranks, %.3g on rank 0\n",
                 static_cast<long long>(summary["steps_this_run"].get<std::int64_t>()), summary["wall_seconds"].get<double>(),
                 summary["particle_steps_per_second"].get<double>(),
                 summary["rank0_particle_steps_per_second"].get<double>());
    if (summary.contains("last_picture"))
      std::fprintf(stderr, "grainflow_mpi: picture of the drum: %s\n", summary["last_picture"].get<std::string>().c_str());
    if (summary["status"] == "interrupted" && summary.contains("checkpoint"))
      std::fprintf(stderr, "grainflow_mpi: stopped by a signal at step %lld; go on with: mpiexec -n %d grainflow_mpi run %s --out %s --resume %s\n",
                   static_cast<long long>(summary["steps"].get<std::int64_t>()), mpi.size(), opt.scene.string().c_str(),
                   opt.out.string().c_str(), summary["checkpoint"].get<std::string>().c_str());
  }
  return 0;
}
