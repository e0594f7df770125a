#include "systems/setup/mpi/rank_checkpoints.hpp"

#include <system_error>

#include "systems/output/sample_grid.hpp"
#include "engine/atomic_file.hpp"
#include "engine/mpi/rank_failure.hpp"

namespace gf {

namespace {

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  return std::filesystem::equivalent(a, b, ec);
}
}  // namespace

RankCheckpoints::RankCheckpoints(RankCheckpointSettings s, const MpiContext& mpi) : s_(std::move(s)), mpi_(&mpi) {
  on_every_rank(mpi, [&] {
    if (mpi.rank() == 0) ensure_directory(s_.dir / "checkpoints");
  });
}

void RankCheckpoints::observe(RankSimulation& sim, const RankOutputs& outputs) {
  if (s_.interval <= 0) return;
  const Clock& c = sim.world().clock;
  if (!sample_due(c.t, next_, c.dt)) return;
  while (sample_due(c.t, next_, c.dt)) next_ += s_.interval;
  write(sim, outputs);
}

std::filesystem::path RankCheckpoints::write(RankSimulation& sim, const RankOutputs& outputs) {
  const MpiContext& mpi = *mpi_;
  const Clock& clock = sim.world().clock;
  const std::filesystem::path dir = s_.dir / "checkpoints";
  const std::filesystem::path part = dir / rank_part_name(clock.step, mpi.rank());
  CheckpointWriter out;
  sim.save(out);
  outputs.save(out);
  out.value("rank_checkpoints.next", next_);
  on_every_rank(mpi, [&] { out.write(part); });
  on_every_rank(mpi, [&] {
    if (mpi.rank() != 0) return;
    RankCheckpointIndex index{mpi.size(), clock.step, clock.t, {}};
    for (int r = 0; r < mpi.size(); ++r) index.parts.push_back(rank_part_name(clock.step, r));
    if (s_.keep_all) write_rank_index(dir / rank_index_copy_name(clock.step), index);
    write_rank_index(index_path(), index);
  });
  // No index names the previous part now: a part that cannot be removed is only left over.
  std::error_code ec;
  if (!s_.keep_all && !previous_.empty() && !same_file(previous_, part)) std::filesystem::remove(previous_, ec);
  previous_ = part;
  last_step_ = clock.step;
  ++written_;
  return index_path();
}

void RankCheckpoints::restore(const CheckpointReader& part, const std::filesystem::path& index) {
  next_ = part.value<double>("rank_checkpoints.next");
  if (same_file(index, index_path())) previous_ = part.file();
}

}  // namespace gf
