#include "systems/output/mpi/rank_checkpoint_index.hpp"

#include <cstdio>

#include "engine/mpi/rank_failure.hpp"

namespace gf {

namespace {

const char* kIndexFix = "give grainflow_mpi --resume the index DIR/checkpoints/checkpoint_ranks.gfc that a run on several ranks wrote";

std::vector<char> joined(const std::vector<std::string>& names) {
  std::vector<char> out;
  for (const std::string& n : names) {
    out.insert(out.end(), n.begin(), n.end());
    out.push_back('\n');
  }
  return out;
}

std::vector<std::string> split(const std::vector<char>& bytes) {
  std::vector<std::string> out;
  std::string name;
  for (const char c : bytes) {
    if (c != '\n') {
      name.push_back(c);
      continue;
    }
    out.push_back(name);
    name.clear();
  }
  return out;
}

// A part's name is a plain file name in the index's folder.
bool plain_name(const std::string& n) {
  return !n.empty() && n != "." && n != ".." && n.find('/') == std::string::npos && n.find('\0') == std::string::npos;
}

std::string ranks_fix(std::int32_t ranks) {
  const std::string n = std::to_string(ranks);
  return "resume on " + n + " ranks (mpiexec -n " + n + " grainflow_mpi run SCENE --out DIR --resume FILE); to go on "
         "with another rank count, start a new run from the final_state.csv that run wrote (a [[fill]] of "
         "kind = \"file\"), which continues the state but not bit for bit";
}

}  // namespace

std::string rank_part_name(std::int64_t step, int rank) {
  char name[64];
  std::snprintf(name, sizeof name, "checkpoint_%012lld_rank%04d.gfc", static_cast<long long>(step), rank);
  return name;
}

std::string rank_index_copy_name(std::int64_t step) {
  char name[48];
  std::snprintf(name, sizeof name, "checkpoint_ranks_%012lld.gfc", static_cast<long long>(step));
  return name;
}

void write_rank_index(const std::filesystem::path& file, const RankCheckpointIndex& index) {
  CheckpointWriter out;
  out.value("rank_checkpoint.ranks", index.ranks);
  out.value("rank_checkpoint.step", index.step);
  out.value("rank_checkpoint.time", index.time);
  out.vector("rank_checkpoint.parts", joined(index.parts));
  out.write(file);
}

RankCheckpointIndex read_rank_index(const std::filesystem::path& file) {
  const CheckpointReader in(file);
  if (in.has("rank.ranks")) in.fail("it is one rank's part of a checkpoint, not its index", kIndexFix);
  if (!in.has("rank_checkpoint.ranks"))
    in.fail("it is a checkpoint of a one-rank run, not the index of a run on several ranks",
            "resume it with grainflow run SCENE --resume FILE, or " + std::string(kIndexFix));
  RankCheckpointIndex index;
  index.ranks = in.value<std::int32_t>("rank_checkpoint.ranks");
  index.step = in.value<std::int64_t>("rank_checkpoint.step");
  index.time = in.value<double>("rank_checkpoint.time");
  std::vector<char> names;
  in.vector("rank_checkpoint.parts", names);
  index.parts = split(names);
  bool plain = index.ranks > 0 && index.parts.size() == static_cast<std::size_t>(index.ranks);
  for (const std::string& n : index.parts) plain = plain && plain_name(n);
  if (!plain) in.fail("it does not name one part per rank", "resume from an earlier checkpoint");
  return index;
}

std::unique_ptr<CheckpointReader> open_rank_part(const std::filesystem::path& index, const MpiContext& mpi) {
  std::unique_ptr<CheckpointReader> part;
  on_every_rank(mpi, [&] {
    const RankCheckpointIndex idx = read_rank_index(index);
    if (idx.ranks != mpi.size())
      throw CheckpointError(index.string() + ": it was written by a run on " + std::to_string(idx.ranks) +
                            " ranks, this run has " + std::to_string(mpi.size()) + ". Fix: " + ranks_fix(idx.ranks));
    part = std::make_unique<CheckpointReader>(index.parent_path() / idx.parts[static_cast<std::size_t>(mpi.rank())]);
    if (part->value<std::int64_t>("rank.clock.step") != idx.step)
      part->fail("it holds step " + std::to_string(part->value<std::int64_t>("rank.clock.step")) + ", its index " +
                     index.string() + " step " + std::to_string(idx.step),
                 "resume from an index and parts of one checkpoint");
  });
  return part;
}

}  // namespace gf
