#include "systems/output/mpi/rank_outputs.hpp"

#include "engine/atomic_file.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "systems/output/mpi/rank_final_state.hpp"

namespace gf {

namespace {
// The run's folder made by rank 0 before anything is written into it.
const std::filesystem::path& made_folder(const std::filesystem::path& out, const MpiContext& mpi) {
  on_every_rank(mpi, [&] {
    if (mpi.rank() == 0) ensure_directory(out);
  });
  return out;
}
}  // namespace

RankOutputs::RankOutputs(const DemScene& s, std::filesystem::path out, const MpiContext& mpi)
    : scene_(&s), out_(made_folder(out, mpi)), mpi_(&mpi), series_(scene_series_settings(s, out_), mpi) {
  if (s.output.frame_interval > 0) frames_.emplace(out_, s.output.frame_interval, s.output.fields, mpi);
}

void RankOutputs::observe(World& w) {
  series_.observe(w);
  if (frames_) frames_->observe(w.grains, w.clock.t, w.clock.dt);
}

const SeriesRow& RankOutputs::finish(World& w) {
  const SeriesRow& row = series_.finish(w);
  if (frames_) frames_->finish(w.grains, w.clock.t);
  write_rank_final_state(out_ / "final_state.csv", w.grains, *scene_, *mpi_);
  return row;
}

}  // namespace gf
