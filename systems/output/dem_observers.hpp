// Observers of a DEM run, scheduled after each step: the time series (with the stability checks
// every long run needs) and the VTK frames. Each decides itself whether it is due.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "engine/checkpoint_file.hpp"
#include "engine/system.hpp"
#include "systems/analysis/metrics.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/vtk_frames.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// A run that became unphysical; the message says what broke, when, and what to change.
class StabilityError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SeriesRow {
  double time = 0, angle = 0, ke_translational = 0, ke_rotational = 0;
  std::int64_t pair_contacts = 0, wall_contacts = 0;
  double max_overlap_ratio = 0, segregation_index = 0;
  bool valid = false;
};

struct SeriesSettings {
  std::optional<std::filesystem::path> csv;  // none: checks only
  double interval = 0;                       // s between rows and checks
  int segregation_type = -1;
  double segregation_cell = 0;
  double max_overlap = 0.1;
  std::optional<std::size_t> resume_rows;  // continue an existing csv, keeping this many rows
};

class SeriesOutput : public SystemBase<SeriesOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Mass, Species, NeighborList, Walls, Clock>;
  using Writes = gf::Writes<SeriesRow>;
  explicit SeriesOutput(SeriesSettings s);
  std::string_view name() const override { return "series_output"; }
  void run(World& world) override;
  // Samples the last state too (summary.json reports it) unless the latest row already is it.
  void finish(World& world);
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  void sample(World& world);
  SeriesSettings s_;
  std::unique_ptr<SeriesCsv> csv_;
  double next_ = 0;
  std::size_t rows_ = 0;  // written to the csv by this run and the runs it continues
};

class FrameOutput : public SystemBase<FrameOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, ParticleId, Force, WallForce, Clock>;
  using Writes = gf::Writes<FrameSeries>;
  FrameOutput(std::filesystem::path dir, double interval, FrameFields fields);
  std::string_view name() const override { return "frame_output"; }
  void run(World& world) override;
  // Writes the last state as a frame unless the latest frame already shows it.
  void finish(World& world);
  std::size_t frames() const { return series_.count(); }
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  FrameSeries series_;
  double interval_;
  FrameFields fields_;
  double next_ = 0;
  double last_written_ = -1;
};

}  // namespace gf
