// Observers of a DEM run, scheduled after each step: the time series, the VTK frames and the drum
// pictures; each decides itself whether it is due. (The stability checks run inside the step:
// stability_report.hpp.)
#pragma once

#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "engine/checkpoint_file.hpp"
#include "engine/run_loop.hpp"
#include "engine/system.hpp"
#include "systems/analysis/free_surface.hpp"
#include "systems/analysis/metrics.hpp"
#include "systems/analysis/mixing.hpp"
#include "systems/analysis/pattern.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/output/drum_picture.hpp"
#include "systems/output/picture_legend.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/wall_loads_csv.hpp"
#include "systems/output/wall_surfaces.hpp"
#include "systems/output/vtk_frames.hpp"
#include "systems/walls/walls.hpp"

namespace gf {



struct SeriesRow {
  double time = 0, angle = 0, ke_translational = 0, ke_rotational = 0;
  std::int64_t pair_contacts = 0, wall_contacts = 0;
  double max_overlap_ratio = 0, segregation_index = 0;
  // Drum pattern (scenes with a drum and two species, else has_pattern is false): pattern is the
  // PatternKind (-1 undecided, 0 moon, 1 petals), petals the lobe count, surface_angle in rad.
  bool has_pattern = false;
  int pattern = -1, petals = 0;
  double pattern_contrast = std::numeric_limits<double>::quiet_NaN();
  double surface_angle = std::numeric_limits<double>::quiet_NaN();
  FreeSurface surface;  // the free surface's level, bulge and speed (free_surface.hpp), with the pattern
  std::array<int, kRingRadii.size()> ring_lobes{};  // Pattern::ring_lobes
  // Binary mixtures (has_mixing): Lacey's index of the larger species over cubic cells of edge
  // lacey_cell (m) holding lacey_cell_grains grains on average (mixing.hpp); with a drum also the
  // radial and depth segregation indices of the larger species in the drum's cross-section.
  bool has_mixing = false;
  double lacey_index = std::numeric_limits<double>::quiet_NaN();
  double lacey_cell_grains = std::numeric_limits<double>::quiet_NaN();
  double lacey_cell = std::numeric_limits<double>::quiet_NaN();
  double radial_segregation = std::numeric_limits<double>::quiet_NaN();
  double depth_segregation = std::numeric_limits<double>::quiet_NaN();
  // Continuous scenes (has_flow): the grains and their mass in the table (the hold-up), the mass fed
  // and discharged so far, and the feeds' backlog (kg owed but not yet placed).
  bool has_flow = false;
  std::int64_t grains = 0;
  double holdup_mass = 0, fed_mass = 0, discharged_mass = 0, feed_backlog = 0;
  bool valid = false;
};

struct SeriesSettings {
  std::optional<std::filesystem::path> csv;  // none: checks only
  double interval = 0;                       // s between rows and checks
  int segregation_type = -1;
  double segregation_cell = 0;
  std::optional<std::size_t> resume_rows;  // continue an existing csv, keeping this many rows
  bool pattern = false;  // classify the drum pattern and the radial segregation at each row (needs a drum wall)
                         // and write the free surface's rows to surface.csv beside the csv
  double resume_time = std::numeric_limits<double>::quiet_NaN();  // s, the checkpoint's clock when resuming
  PatternSettings pattern_settings;
  double mixing_cell = 0;      // m; > 0: Lacey's index of segregation_type over cells of this edge
  int mixing_min_grains = 10;  // cells with fewer grains are left out of it
  bool flow = false;           // hold-up columns from the FlowState resource (a scene with feeds or outlets)
  // walls.csv beside the csv (wall_loads_csv.hpp): the walls' names, the analytic ones first.
  std::vector<std::string> wall_names;
  std::size_t analytic_walls = 0;
};

// Rotation angle (rad) of the first rotating wall at time t, else of the first rotating mesh wall
// (omega t while rotation is on, as the mesh contacts place it); 0 if none rotates.
double rotation_angle(const Walls& walls, double t, const MeshWalls* meshes = nullptr);

// The columns of series.csv for these settings, in order.
std::vector<std::string> series_columns(const SeriesSettings& s);

// The columns of surface.csv (scenes with the pattern columns).
std::vector<std::string> surface_columns();

class SeriesOutput : public SystemBase<SeriesOutput>, public Checkpointable {
 public:
  using Reads =
      gf::Reads<Position, Velocity, AngularVelocity, Radius, Mass, Species, NeighborList, Walls, MeshWalls, Gravity,
                FlowState, MeshWallLoads>;
  using Writes = gf::Writes<SeriesRow>;
  explicit SeriesOutput(SeriesSettings s);
  std::string_view name() const override { return "series_output"; }
  void run(World& world, const StepContext& now) override;
  bool samples(const World& world, const StepContext& now) const override;
  // Samples the last state too (summary.json reports it) unless the latest row already is it.
  void finish(World& world);
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  void sample(World& world, double t);
  void sample_mixing(const Grains& g, SeriesRow& row) const;
  void sample_pattern(World& world, SeriesRow& row) const;
  static void sample_flow(World& world, SeriesRow& row);
  void write(const SeriesRow& row);
  bool mixing() const { return s_.mixing_cell > 0; }
  bool sampled_at(double t, double dt) const;  // the row at time t was written (t the clock of a step)
  SeriesSettings s_;
  std::unique_ptr<SeriesCsv> csv_;
  std::unique_ptr<SeriesCsv> surface_csv_;  // surface.csv; opened by restore() when resuming
  std::unique_ptr<WallLoadsCsv> walls_csv_;  // walls.csv; the same
  double next_ = 0;
  std::size_t rows_ = 0;  // written to the csv by this run and the runs it continues
};

class FrameOutput : public SystemBase<FrameOutput>, public Checkpointable {
 public:
  using Reads =
      gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, ParticleId, Force, WallForce, Walls, MeshWalls>;
  using Writes = gf::Writes<FrameSeries>;
  // `key` names its sections in a checkpoint (another when a checkpoint holds two frame series).
  FrameOutput(std::filesystem::path dir, double interval, FrameFields fields, std::string key = "frame_output");
  std::string_view name() const override { return "frame_output"; }
  void run(World& world, const StepContext& now) override;
  bool samples(const World& world, const StepContext& now) const override;
  // Writes the last state as a frame unless the latest frame already shows it.
  void finish(World& world);
  std::size_t frames() const { return series_.count(); }
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  void write(World& world, double t);
  FrameSeries series_;
  double interval_;
  FrameFields fields_;
  std::string key_;
  double next_ = 0;
  double last_written_ = -1;
  // The walls at the frames' times (walls.pvd, wall_surfaces.hpp), opened at the first frame of a
  // world with walls; one file when nothing moves.
  std::unique_ptr<FrameSeries> walls_;
  bool walls_checked_ = false;
  SceneBox box_;
  std::vector<double> resumed_times_;
};

// The PNG files a PictureOutput writes (a tag for the schedule).
struct DrumPictures {};

struct PictureSettings {
  std::filesystem::path dir;    // the run's pictures/ folder
  std::vector<double> angles;   // rad, sorted
  double interval = 0;          // rad, 0 = none
  PictureOptions options;
  std::string legend;           // species colours, for the PNG's Comment entry
  std::vector<std::string> species_labels;  // the legend's: name and diameter, per species
};

// Draws the drum (the first rotating inner cylinder, else the first one) when the rotation angle of
// the first rotating wall reaches each requested angle: pictures/angle_XX.XX.png, named after the
// requested angle (the state drawn is the first step at or past it, at most omega dt later).
class PictureOutput : public SystemBase<PictureOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<Position, Velocity, Radius, Species, Walls, Gravity>;
  using Writes = gf::Writes<DrumPictures>;
  explicit PictureOutput(PictureSettings s);
  std::string_view name() const override { return "picture_output"; }
  void run(World& world, const StepContext& now) override;
  bool samples(const World& world, const StepContext& now) const override;
  // The drum's rotation angle now when a picture is due there (every rank of a run on several ranks
  // computes the same), else nothing.
  std::optional<double> due(const Walls& walls, const StepContext& now) const;
  // Every target up to `angle` drawn from g's owned rows and written, then passed; with write =
  // false only passed (the ranks that do not hold the gathered grains).
  void draw(const Grains& g, const Walls& walls, const Gravity& gravity, const StepContext& now, double angle,
            bool write = true);
  std::size_t pictures() const { return written_; }
  // The picture's legend at time t (picture_legend.hpp): time, angle, turning, scale, colours.
  PictureLegend legend(const Walls& walls, std::size_t drum, const DrumSection& section, double t) const;
  // The file this run drew last (empty if it drew none).
  const std::filesystem::path& last_picture() const { return last_; }
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  double next_target() const;
  void pass(double target);  // the target counted as drawn
  PictureSettings s_;
  std::size_t next_angle_ = 0;
  std::int64_t next_multiple_ = 0;
  std::size_t written_ = 0;
  std::filesystem::path last_;
  std::vector<double> speed_;
};

}  // namespace gf
