#include "systems/setup/mpi/rank_outputs.hpp"

#include "engine/atomic_file.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "systems/setup/mpi/gathered_grains.hpp"
#include "systems/setup/dem_output_settings.hpp"
#include "systems/setup/mpi/rank_final_state.hpp"

namespace gf {

namespace {
// The run's folder made by rank 0 before anything is written into it.
const std::filesystem::path& made_folder(const std::filesystem::path& out, const MpiContext& mpi) {
  on_every_rank(mpi, [&] {
    if (mpi.rank() == 0) ensure_directory(out);
  });
  return out;
}

// The series' settings, continuing a csv when a resumed run gives its rows.
SeriesSettings series_settings(const DemScene& s, const std::filesystem::path& out, std::optional<std::size_t> rows) {
  SeriesSettings ss = scene_series_settings(s, out);
  ss.resume_rows = rows;
  return ss;
}
}  // namespace

RankOutputs::RankOutputs(const DemScene& s, std::filesystem::path out, const MpiContext& mpi,
                         std::optional<RankOutputRows> rows)
    : scene_(&s),
      out_(made_folder(out, mpi)),
      mpi_(&mpi),
      series_(series_settings(s, out_, rows ? std::optional<std::size_t>(rows->series) : std::nullopt), mpi) {
  if (s.output.frame_interval > 0) frames_.emplace(out_, s.output.frame_interval, s.output.fields, mpi);
  if (scene_draws_pictures(s)) pictures_.emplace(scene_picture_settings(s, out_));
  on_every_rank(mpi, [&] {
    if (mpi.rank() != 0) return;
    if (!s.flow.outlets.empty())
      residence_.emplace(out_ / "residence.csv", rows ? std::optional<std::size_t>(rows->residence) : std::nullopt);
    if (s.layers)
      layers_.emplace(out_ / "layers.csv", *s.layers, rows ? std::optional<std::size_t>(rows->layers) : std::nullopt);
  });
}

RankOutputRows RankOutputs::written_rows(const CheckpointReader& part) {
  RankOutputRows r;
  r.series = part.value<std::uint64_t>("rank_series.rows");
  if (part.has("residence_output.rows")) r.residence = part.value<std::uint64_t>("residence_output.rows");
  if (part.has("layer_output.rows")) r.layers = part.value<std::uint64_t>("layer_output.rows");
  return r;
}

void RankOutputs::save(CheckpointWriter& out) const {
  series_.save(out);
  if (frames_) frames_->save(out);
  if (pictures_) pictures_->save(out);
  if (residence_) residence_->save(out);
  if (layers_) layers_->save(out);
}

void RankOutputs::restore(const CheckpointReader& part) {
  on_every_rank(*mpi_, [&] {
    series_.restore(part);
    if (!frames_) return;
    if (!part.has("rank_frames.next"))
      part.fail("the run that wrote it had no frames", "resume with output.frame_interval = 0, as that run had");
    frames_->restore(part);
  });
  on_every_rank(*mpi_, [&] {
    if (!pictures_) return;
    if (!part.has("picture_output.next_angle"))
      part.fail("the run that wrote it drew no pictures",
                "resume without output.picture_angles and output.picture_interval, as that run had");
    pictures_->restore(part);
  });
  on_every_rank(*mpi_, [&] {
    if (residence_) residence_->restore(part);
    if (!layers_) return;
    if (!part.has("layer_output.next"))
      part.fail("the run that wrote it had no [analysis.layers]", "resume with the scene of the run that wrote it");
    layers_->restore(part);
  });
  if (frames_) frames_->rewrite_index();
}

void RankOutputs::observe(World& w) {
  series_.observe(w);
  if (frames_) frames_->observe(w.grains, w.clock.t, w.clock.dt);
  const StepContext now = next_step(w.clock);
  // Every rank holds every rank's records (rank_flow.hpp): rank 0 writes them, the others drop them.
  FlowState* flow = w.resources.find<FlowState>();
  if (flow && !flow->exits.empty())
    on_every_rank(*mpi_, [&] {
      if (residence_) residence_->run(w, now);
      else flow->exits.clear();
    });
  // Rank 0 says when a layer sample is due; every rank's grains then go there.
  if (scene_->layers && mpi_->max(layers_ && layers_->due(w.clock.t, w.clock.dt) ? 1.0 : 0.0) > 0.0) {
    const Grains all = gather_shapes(w.grains, *mpi_);
    on_every_rank(*mpi_, [&] {
      if (layers_) layers_->sample(all, w.clock.t, w.clock.dt);
    });
  }
  if (!pictures_) return;
  const Walls& walls = w.resources.get<Walls>();
  const auto angle = pictures_->due(walls, now);
  if (!angle) return;
  const Grains all = gather_shapes(w.grains, *mpi_);
  on_every_rank(*mpi_, [&] {
    pictures_->draw(all, walls, w.resources.get<Gravity>(), now, *angle, mpi_->rank() == 0);
  });
}

const SeriesRow& RankOutputs::finish(World& w) {
  const SeriesRow& row = series_.finish(w);
  if (frames_) frames_->finish(w.grains, w.clock.t);
  write_rank_final_state(out_ / "final_state.csv", w.grains, *mpi_);
  return row;
}

}  // namespace gf
