// Checkpoints of a run on several ranks at the scene's output.checkpoint_interval (and, when the
// caller asks, at the end of the run): each rank writes its part, then rank 0 the index naming them
// (rank_checkpoint_index.hpp). Once the new index is on disk each rank removes its part of the set
// the index named before (unless output.checkpoint_keep_all, which also keeps a numbered copy of
// every index). Scheduled after the other outputs, so their state is saved as of the same step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "engine/checkpoint_file.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"
#include "systems/output/mpi/rank_checkpoint_index.hpp"
#include "systems/setup/mpi/rank_outputs.hpp"

namespace gf {

struct RankCheckpointSettings {
  std::filesystem::path dir;  // the run folder; files go to dir/checkpoints
  double interval = 0;        // s of simulated time between checkpoints; 0: only when asked (write)
  bool keep_all = false;      // keep every set and a numbered copy of its index
};

class RankCheckpoints {
 public:
  // Rank 0 creates dir/checkpoints. Collective; RankFailure on every rank if it cannot.
  RankCheckpoints(RankCheckpointSettings s, const MpiContext& mpi);
  // At the start of the main stage and after each of its steps, after the outputs: writes a
  // checkpoint when the clock reached the next checkpoint time (t = k interval). Collective.
  void observe(RankSimulation& sim, const RankOutputs& outputs);
  // Writes a checkpoint of the current state now and returns its index. Collective; a part or
  // index that cannot be written is a RankFailure on every rank naming it (the previous set and
  // index are then left as they were).
  std::filesystem::path write(RankSimulation& sim, const RankOutputs& outputs);
  std::size_t written() const { return written_; }
  // Whether this run's latest checkpoint is of the given step (then another would be the same).
  bool holds(std::int64_t step) const { return written_ > 0 && last_step_ == step; }
  std::filesystem::path index_path() const { return s_.dir / "checkpoints" / kRankIndexName; }

  // Takes back the next checkpoint time from this rank's part of the checkpoint at `index`; when
  // that is this run's latest index, the part is the one the next checkpoint replaces. Local.
  void restore(const CheckpointReader& part, const std::filesystem::path& index);

 private:
  RankCheckpointSettings s_;
  const MpiContext* mpi_;
  double next_ = 0;
  std::size_t written_ = 0;
  std::int64_t last_step_ = -1;
  std::filesystem::path previous_;  // this rank's part of the set the index names now, if this run's
};

}  // namespace gf
