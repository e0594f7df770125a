// series.csv of a run on several ranks: the columns and rows of the one-rank run's SeriesOutput
// (dem_observers.hpp) for the same scene, written by rank 0 at the scene's series_interval.
//
// Each row's measures are reduced across the ranks: the kinetic energies and the contact counts are
// sums over the ranks' owned rows (a pair across ranks is listed on one rank only, the higher, so it
// counts once), the largest overlap ratio is the largest of the ranks'. The measures that need every
// grain at once (segregation and Lacey's indices, the drum's pattern, surface angle and radial and
// depth segregation) are computed on rank 0 from the grains gathered there, in id order, and only
// for the rows written; only position, radius, species and id travel. With feeds and outlets the
// grains and hold-up mass are sums over the ranks, the fed, discharged and owed masses the flow's
// state, which every rank holds alike (rank_flow.hpp). The sums are taken in
// another order than on one rank, so the values agree to round-off, not bit for bit. walls.csv, beside
// it, holds the walls' loads summed over the ranks (rank_wall_loads.hpp), one row per series row.
#pragma once

#include <filesystem>
#include <memory>

#include "engine/checkpoint_file.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "engine/world.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

class RankSeries {
 public:
  // Rank 0 creates the csv with its header (none when the scene has no series_interval), or with
  // s.resume_rows continues it, keeping that many rows (SeriesCsv::resume). Collective; RankFailure
  // on every rank if it cannot be created.
  RankSeries(SeriesSettings s, const MpiContext& mpi);
  // Writes a row when the clock reached the next sampling time (t = k interval, as on one rank).
  // Collective (called by every rank after every step, and once before the first).
  void observe(World& w);
  // Samples the last state unless the latest row is it, and returns it: whole on rank 0; elsewhere
  // the measures of gathered grains keep their defaults. Collective.
  const SeriesRow& finish(World& w);
  std::size_t rows() const { return rows_; }
  // The next sampling time, the rows written and the latest row, in a checkpoint part and back.
  void save(CheckpointWriter& out) const;
  void restore(const CheckpointReader& in);
  const std::vector<std::string>& columns() const { return columns_; }

 private:
  void sample(World& w, double t);
  void sample_whole(const Grains& all, World& w, SeriesRow& row) const;
  bool needs_all() const;
  SeriesSettings s_;
  const MpiContext* mpi_;
  std::vector<std::string> columns_;
  std::unique_ptr<SeriesCsv> csv_;  // rank 0 only
  std::unique_ptr<WallLoadsCsv> walls_csv_;  // walls.csv; rank 0 only
  SeriesRow row_;
  double next_ = 0;
  std::size_t rows_ = 0;
};

}  // namespace gf
