// The checkpoints of a run on several ranks, in DIR/checkpoints: one part per rank,
// checkpoint_<step>_rank<r>.gfc (RankSimulation::save and the outputs' state, in the checkpoint
// file format of engine/checkpoint_file.hpp), and the index checkpoint_ranks.gfc naming the parts of
// the latest whole set with its step, time and rank count. The parts are written first and the
// index last, each atomically, so the index only ever names a set whose every part is on disk.
// A part is raw memory of the build that wrote it (read back by the same build): on as many ranks
// each rank reads its own part; on another number of ranks the parts are shared out among the
// ranks and their rows and springs go to the new boxes (RankSimulation::restore_portable).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/mpi/mpi_context.hpp"

namespace gf {

inline constexpr const char* kRankIndexName = "checkpoint_ranks.gfc";

struct RankCheckpointIndex {
  std::int32_t ranks = 0;
  std::int64_t step = 0;
  double time = 0;                 // s
  std::vector<std::string> parts;  // per rank, a file name in the index's folder
};

// checkpoint_<step, 12 digits>_rank<rank, 4 digits>.gfc
std::string rank_part_name(std::int64_t step, int rank);
// checkpoint_ranks_<step, 12 digits>.gfc: the numbered copy of the index output.checkpoint_keep_all keeps.
std::string rank_index_copy_name(std::int64_t step);

// Written atomically (WriteError naming the file).
void write_rank_index(const std::filesystem::path& file, const RankCheckpointIndex& index);
// CheckpointError naming the file and the fix when it is unreadable, corrupt, a one-rank checkpoint
// or one rank's part rather than an index.
RankCheckpointIndex read_rank_index(const std::filesystem::path& file);

// Collective: every rank reads the index and opens its own part, checking that the index is for
// this many ranks and the part is its rank's of the same step. A failure on any rank is a RankFailure
// on every rank; rank 0's names each file and the fix.
std::unique_ptr<CheckpointReader> open_rank_part(const std::filesystem::path& index, const MpiContext& mpi);

}  // namespace gf
