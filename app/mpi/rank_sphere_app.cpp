#include "app/mpi/rank_sphere_app.hpp"

#include <array>
#include <chrono>
#include <cstdlib>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/run_model.hpp"
#include "app/run_outcome.hpp"
#include "engine/atomic_file.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/output/mpi/rank_checkpoint_index.hpp"
#include "systems/output/summary_json.hpp"
#include "systems/setup/mpi/rank_checkpoints.hpp"
#include "systems/setup/mpi/rank_outputs.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"

namespace gf {

namespace {

// Runs a collective phase of the run: a failure every rank shares (RankFailure: a file that could not
// be written) becomes a WriteError for the skeleton to report with how to go on; a run that became
// unphysical, or any other failure, on one rank stops every rank.
[[noreturn]] void stop_every_rank(const MpiContext& mpi, const char* what, int status) {
  std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), what);
  MPI_Abort(mpi.comm(), status);
  std::abort();  // MPI_Abort does not return
}

template <class F>
decltype(auto) collective(const MpiContext& mpi, F&& f) {
  try {
    return f();
  } catch (const RankFailure& e) {
    throw WriteError(e.what());
  } catch (const StabilityError& e) {
    stop_every_rank(mpi, e.what(), 3);
  } catch (const std::exception& e) {
    stop_every_rank(mpi, e.what(), 2);
  }
}

// Grains on ranks (RankSimulation), for the run skeleton (run_model.hpp). Every call is collective
// unless said otherwise.
class RankSphereModel final : public Model {
 public:
  RankSphereModel(DemScene scene, const MpiContext& mpi, double rebalance)
      : sim_(std::move(scene), mpi), mpi_(mpi), rebalance_(rebalance) {
    sim_.set_rebalance(rebalance);
    grains_ = sim_.total_grains();
  }

  std::string_view kind() const override { return "spheres"; }
  World& world() override { return sim_.world(); }
  RunCounts counts() override { return {sim_.total_grains(), 0}; }
  std::vector<Schedule*> schedules() override { return sim_.schedules(); }

  std::unique_ptr<CheckpointReader> resume(const std::filesystem::path& index) override;
  void restore(const CheckpointReader& part) override { sim_.restore(part); }
  std::string resumed_note() const override {
    if (!other_ranks_) return "";
    return ", written on " + std::to_string(other_ranks_) + " ranks: its rows and springs shared out to this run's boxes";
  }
  std::string opening(std::size_t threads, int ranks) override {  // local
    char line[160];
    std::snprintf(line, sizeof line, "%lld grains on %d ranks, %zu threads each", static_cast<long long>(grains_),
                  ranks, threads);
    return sim_.scene().file.string() + ": " + line;
  }
  void open_summary(nlohmann::json& summary) override {  // local
    summary["grains"] = grains_;
    summary["threads_per_rank"] = threads_in_use();
  }
  StageReport settle(double) override {
    const auto t0 = std::chrono::steady_clock::now();
    StageReport r;
    r.steps = collective(mpi_, [&] { return sim_.settle(); });
    r.wall_seconds = mpi_.max(seconds_since(t0));
    return r;
  }
  void observe(Schedule& observers, const std::filesystem::path& out, const CheckpointReader* from) override;

  std::int64_t last_step() const override { return scene_.main_steps(); }
  double rows(const World& w) const override { return static_cast<double>(w.grains.n_owned); }  // this rank's
  StageReport run(const StageOptions& stage) override;

  bool checkpoint_at_end() const override { return scene_.output.checkpoint_at_end; }
  std::filesystem::path write_checkpoint() override {
    return collective(mpi_, [&] {
      if (!checkpoints_->holds(sim_.world().clock.step)) checkpoints_->write(sim_, *outputs_);
      return checkpoints_->index_path();
    });
  }
  std::size_t checkpoints_written() const override { return checkpoints_ ? checkpoints_->written() : 0; }
  std::filesystem::path go_on_from(const std::filesystem::path&, const CheckpointReader*) const override {
    return checkpoints_written() > 0 ? checkpoints_->index_path() : resumed_index_;
  }

  void finish_outputs() override {
    last_ = &collective(mpi_, [&]() -> const SeriesRow& { return outputs_->finish(sim_.world()); });
  }
  void close_summary(nlohmann::json& summary, const StageReport& main) override;
  std::string rate(const nlohmann::json& summary) const override {
    char text[96];
    std::snprintf(text, sizeof text, "%.3g particle-steps/s on all ranks, %.3g on rank 0",
                  summary["particle_steps_per_second"].get<double>(), summary["rank0_particle_steps_per_second"].get<double>());
    return text;
  }
  std::string last_words() const override {
    if (!outputs_ || outputs_->last_picture().empty()) return "";
    return "picture of the drum: " + outputs_->last_picture().string();
  }

 private:
  RankSimulation sim_;
  const DemScene& scene_ = sim_.scene();
  const MpiContext& mpi_;
  double rebalance_ = 0;
  std::int64_t grains_ = 0;  // at the start, over every rank
  int other_ranks_ = 0;      // the rank count of the checkpoint resumed, when it differs from this run's
  std::filesystem::path resumed_index_;
  std::optional<RankOutputRows> resumed_rows_;
  std::unique_ptr<RankOutputs> outputs_;
  std::unique_ptr<RankCheckpoints> checkpoints_;
  const SeriesRow* last_ = nullptr;
  RankCounters before_;         // the counters at the main stage's start
  std::int64_t kept_before_ = 0;
  double mine_ = 0, own_steps_ = 0;  // this rank's main-stage wall time and particle-steps
};

// A checkpoint's state on every rank: each rank's part opened and restored; on another rank count,
// part 0 gives every rank the clock and the outputs' state, and the parts are shared out among the
// ranks to be read (RankSimulation::restore_portable). A RankFailure on every rank when any part
// cannot be read (rank 0's message names the files).
std::unique_ptr<CheckpointReader> RankSphereModel::resume(const std::filesystem::path& index) {
  RankCheckpointIndex idx;
  on_every_rank(mpi_, [&] { idx = read_rank_index(index); });
  std::unique_ptr<CheckpointReader> part;
  if (idx.ranks == mpi_.size()) {
    part = open_rank_part(index, mpi_);
    on_every_rank(mpi_, [&] { sim_.restore(*part); });
  } else {
    on_every_rank(mpi_, [&] { part = std::make_unique<CheckpointReader>(index.parent_path() / idx.parts[0]); });
    std::vector<std::filesystem::path> mine;
    for (std::size_t k = static_cast<std::size_t>(mpi_.rank()); k < idx.parts.size(); k += static_cast<std::size_t>(mpi_.size()))
      mine.push_back(index.parent_path() / idx.parts[k]);
    sim_.restore_portable(*part, mine);
    other_ranks_ = idx.ranks;
  }
  on_every_rank(mpi_, [&] { resumed_rows_ = RankOutputs::written_rows(*part); });
  resumed_index_ = index;
  grains_ = sim_.total_grains();
  return part;
}

// The outputs and checkpoints, their state taken from the part when the run resumes. A set of parts
// of another rank count is not this run's to replace: the next set leaves it.
void RankSphereModel::observe(Schedule&, const std::filesystem::path& out, const CheckpointReader* from) {
  const DemScene& scene = sim_.scene();
  outputs_ = std::make_unique<RankOutputs>(scene, out, mpi_, resumed_rows_);
  checkpoints_ = std::make_unique<RankCheckpoints>(
      RankCheckpointSettings{out, scene.output.checkpoint_interval, scene.output.checkpoint_keep_all}, mpi_);
  if (!from) return;
  outputs_->restore(*from);
  on_every_rank(mpi_, [&] { checkpoints_->restore(*from, other_ranks_ ? std::filesystem::path() : resumed_index_); });
}

// The main stage's steps with the outputs and the checkpoints, observing the start and every step
// after it. A signal on any rank stops every rank after the same step: each step's check is a
// collective maximum over the ranks.
StageReport RankSphereModel::run(const StageOptions& stage) {
  World& world = sim_.world();
  before_ = sim_.counters();
  kept_before_ = world.resources.get<BroadphaseState>().cover.kept;
  mpi_.barrier();
  const auto t0 = std::chrono::steady_clock::now();
  StageReport r = collective(mpi_, [&] {
    StageReport done;
    outputs_->observe(world);
    checkpoints_->observe(sim_, *outputs_);
    for (; done.steps < stage.steps; ++done.steps) {
      if (mpi_.max(stop_requested() ? 1.0 : 0.0) > 0.0) {
        done.interrupted = true;
        break;
      }
      sim_.advance(1);
      outputs_->observe(world);
      checkpoints_->observe(sim_, *outputs_);
    }
    return done;
  });
  mine_ = seconds_since(t0);
  r.wall_seconds = mpi_.max(mine_);
  own_steps_ = sim_.counters().particle_steps - before_.particle_steps;
  r.particle_steps = mpi_.sum(own_steps_);
  return r;
}

// The rank run's own entries (collective: the sums over the ranks).
void RankSphereModel::close_summary(nlohmann::json& summary, const StageReport&) {
  const std::array<double, 3> p = sim_.total_momentum();
  const double energy = sim_.total_kinetic_energy();
  const std::int64_t still = sim_.total_grains();
  const RankCounters& now = sim_.counters();
  const std::int64_t migrated = mpi_.sum(now.migrated - before_.migrated);
  const std::int64_t ghosts = mpi_.sum(now.ghosts);
  if (checkpoints_written() > 0) summary["checkpoint"] = checkpoints_->index_path().string();
  summary["grains_at_end"] = still;
  summary["settle_steps"] = summary["settle"]["steps"];
  summary["settle_wall_seconds"] = summary["settle"]["wall_seconds"];
  summary["rank0_particle_steps_per_second"] = mine_ > 0 ? own_steps_ / mine_ : 0.0;
  summary["rank0_grains_at_end"] = static_cast<std::int64_t>(sim_.grains().n_owned);
  summary["settle_neighbour_rebuilds"] = before_.rebuilds;
  summary["neighbour_rebuilds"] = now.rebuilds - before_.rebuilds;
  summary["neighbour_lists_kept"] = sim_.world().resources.get<BroadphaseState>().cover.kept - kept_before_;
  summary["rows_migrated"] = migrated;
  summary["rebalances"] = now.rebalances - before_.rebalances;
  summary["rebalance_ratio"] = rebalance_;
  summary["ghost_rows_at_end"] = ghosts;
  summary["kinetic_energy"] = energy;
  summary["momentum"] = {p[0], p[1], p[2]};
  summary["series_rows"] = outputs_ ? outputs_->series_rows() : 0;
  summary["frames"] = outputs_ ? outputs_->frames() : 0;
  summary["pictures"] = outputs_ ? outputs_->pictures() : 0;
  if (outputs_ && !outputs_->last_picture().empty()) summary["last_picture"] = outputs_->last_picture().string();
  if (!last_) return;
  summary["final"] = final_row_json(*last_);
  if (const FlowState* f = sim_.world().resources.find<FlowState>())
    summary["flow"] = {{"grains", still},
                       {"holdup_mass", last_->holdup_mass},
                       {"fed_grains", f->fed_grains()},
                       {"fed_mass", f->fed_mass()},
                       {"discharged", f->discharged()},
                       {"discharged_mass", f->discharged_mass()},
                       {"feed_backlog", f->backlog()}};
}

}  // namespace

int run_rank_sphere_command(const CliOptions& opt, DemScene scene, const MpiContext& mpi) {
  RunPlace place;
  place.writer = mpi.rank() == 0;
  place.ranks = mpi.size();
  place.every_process_ends = true;
  place.program = "grainflow_mpi";
  try {
    RankSphereModel model(std::move(scene), mpi, opt.rebalance);
    return run_model(model, opt, place);
  } catch (const RankFailure& e) {  // on every rank: rank 0 says why (the message names the file and the fix)
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // on this rank alone: the others may be waiting for it
    stop_every_rank(mpi, e.what(), 2);
  }
}

}  // namespace gf
