// What a run on several ranks writes into its folder besides summary.json, as `grainflow run` does
// on one: series.csv (rank_series.hpp), the VTK frames in pieces with their .pvtp and frames.pvd
// (rank_frames.hpp), the drum pictures (PictureOutput, drawn by rank 0 from the gathered grains at
// the angles every rank finds due alike), residence.csv (ResidenceOutput on rank 0, which receives
// every rank's records: rank_flow.hpp), layers.csv (LayerOutput on rank 0, sampling the grains
// gathered there when it finds a sample due) and final_state.csv (rank_final_state.hpp). Every call
// is collective; a file that cannot be written stops every rank with a RankFailure (rank_failure.hpp)
// naming it.
#pragma once

#include <filesystem>
#include <optional>

#include "engine/mpi/mpi_context.hpp"
#include "engine/world.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/output/layer_output.hpp"
#include "systems/output/residence_csv.hpp"
#include "systems/output/mpi/rank_frames.hpp"
#include "systems/setup/mpi/rank_series.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// The rows of each csv a resumed run keeps.
struct RankOutputRows {
  std::size_t series = 0, residence = 0, layers = 0;
};

class RankOutputs {
 public:
  // Creates `out` and, for the scene's intervals, series.csv and the frames folder. A resumed run
  // gives the rows its checkpoint's series.csv had (series_rows(part)): later ones are dropped.
  RankOutputs(const DemScene& s, std::filesystem::path out, const MpiContext& mpi,
              std::optional<RankOutputRows> rows = std::nullopt);
  // The rows written up to the checkpoint this part belongs to (residence and layers: part 0's).
  static RankOutputRows written_rows(const CheckpointReader& part);
  // At the start of the main stage and after each of its steps: the rows and frames that are due.
  void observe(World& w);
  // The last state as a row and a frame (unless the latest shows it) and final_state.csv; returns
  // the last row (whole on rank 0).
  const SeriesRow& finish(World& w);
  std::size_t series_rows() const { return series_.rows(); }
  std::size_t frames() const { return frames_ ? frames_->count() : 0; }
  std::size_t pictures() const { return pictures_ ? pictures_->pictures() : 0; }
  // The picture rank 0 drew last (empty on the other ranks and when none was drawn).
  std::filesystem::path last_picture() const { return pictures_ ? pictures_->last_picture() : std::filesystem::path(); }
  // The series' and frames' state (next due times, rows and frames so far) in a checkpoint part.
  void save(CheckpointWriter& out) const;
  // Takes that state back from this rank's part and rewrites frames.pvd to list the frames written
  // up to the checkpoint; a part without frames for a scene with them stops every rank, naming the
  // file. Collective.
  void restore(const CheckpointReader& part);

 private:
  const DemScene* scene_;
  std::filesystem::path out_;
  const MpiContext* mpi_;
  RankSeries series_;
  std::optional<RankFrames> frames_;
  std::optional<PictureOutput> pictures_;
  std::optional<ResidenceOutput> residence_;  // rank 0
  std::optional<LayerOutput> layers_;         // rank 0
};

}  // namespace gf
