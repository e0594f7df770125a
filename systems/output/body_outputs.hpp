// Observers of a run of composite grains, scheduled after each step (each decides itself whether it
// is due): the time series, the state frames and the side-view pictures.
//
// series.csv columns:
//   time                 s of the main stage
//   ke_translational     J, sum of m v^2 / 2 over moving bodies
//   ke_rotational        J, sum of w^T I w / 2 over moving bodies (I the world-frame inertia)
//   contacts             member pairs of two moving bodies touching
//   wall_contacts        moving members touching a plane wall or a fixed body's member
//   max_overlap_ratio    the largest overlap of any contact over the scene's overlap scale: the
//                        smallest outer dimension (bounding-box edge) of the thinnest shape that a moving
//                        body has, the composite grain's "smaller diameter"
//   moving               bodies moving (not fixed, not removed)
//   remaining_fraction   (with analysis.outlet_height) moving bodies whose centre of mass lies above
//                        the outlet height, over the bodies moving at the start of the main stage
// frames/frame_NNNNNN.csv: one row per body (fixed and removed ones too), sorted by id:
//   id, shape (the [[shape]] name), group, layer (-1 for bodies not moving at the start), motion
//   (moving, fixed, removed), x, y, z (m, centre of mass), qw, qx, qy, qz (the unit quaternion that
//   takes the [[shape]]'s own frame to the world, as a scene places shapes), vx, vy, vz (m/s),
//   wx, wy, wz (rad/s, world frame); frames/frames.csv lists frame, time and file. At the same times,
//   bodies/bodies_NNNNNN.vtu (listed by bodies.pvd) holds the members for ParaView (body_vtu.hpp).
#pragma once

#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "engine/checkpoint_file.hpp"
#include "engine/system.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/output/body_picture.hpp"
#include "systems/output/picture_legend.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/output/vtk_frames.hpp"
#include "systems/output/wall_loads_csv.hpp"
#include "systems/output/wall_surfaces.hpp"

namespace gf {

// What a body frame writes of each body beside its state: its shape's name and group, and the rotation
// from its shape's frame to its principal frame (the frame the Bodies table holds it in).
struct BodyFrameLabels {
  std::vector<std::string> shape_name;        // per shape
  std::vector<Eigen::Quaterniond> shape_axes;  // per shape: the principal axes in the shape's frame
  std::vector<std::size_t> shape;              // per body row
  std::vector<int> group;                      // per body row
};

// The last sample of the series, for summary.json.
struct BodySeriesRow {
  double time = 0, ke_translational = 0, ke_rotational = 0;
  std::int64_t contacts = 0, wall_contacts = 0, moving = 0;
  double max_overlap_ratio = 0;
  double remaining_fraction = std::numeric_limits<double>::quiet_NaN();
  bool valid = false;
};

struct BodyEnergies {
  double translational = 0, rotational = 0;  // J, moving bodies
};
BodyEnergies body_kinetic_energy(const Bodies& b);

// Fraction of `initial` bodies that are moving with their centre of mass above `height` (m along
// -gravity); 0 when initial is 0.
double remaining_fraction(const Bodies& b, const Gravity& g, double height, std::size_t initial);

// Five layers (0 lowest .. 4 highest) of equal counts by height along -gravity of the moving bodies
// (ties by row); -1 for the others.
std::vector<int> body_layers(const Bodies& b, const Gravity& g, int layers = 5);

struct BodySeriesSettings {
  std::optional<std::filesystem::path> csv;  // none: the last row only (summary.json)
  double interval = 0;                       // s
  double overlap_scale = 1;                  // m
  std::optional<double> outlet_height;       // m along -gravity
  std::size_t initial_moving = 0;            // the remaining fraction's denominator
  std::optional<std::size_t> resume_rows;    // continue an existing csv, keeping this many rows
  // walls.csv beside the csv (wall_loads_csv.hpp), from BodyContactState's loads: the plane walls'
  // names (none: no file).
  std::vector<std::string> wall_names;
};

class BodySeriesOutput : public SystemBase<BodySeriesOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<BodyPosition, BodyOrientation, BodyVelocity, BodyAngularVelocity, BodyMass, BodyInertia,
                          BodyMotion, BodyContactState, Gravity>;
  using Writes = gf::Writes<BodySeriesRow>;
  explicit BodySeriesOutput(BodySeriesSettings s);
  std::string_view name() const override { return "body_series_output"; }
  void run(World& world, const StepContext& now) override;
  // Samples the last state unless the latest row already is it.
  void finish(World& world);
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  void sample(World& world, double t);
  BodySeriesSettings s_;
  std::unique_ptr<SeriesCsv> csv_;
  std::unique_ptr<WallLoadsCsv> walls_csv_;  // walls.csv, one row per series row
  double next_ = 0;
  std::size_t rows_ = 0;  // written to the csv by this run and the runs it continues
};

// The CSV files of a BodyFrameOutput (a tag for the schedule).
struct BodyFrameFiles {};

class BodyFrameOutput : public SystemBase<BodyFrameOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<BodyPosition, BodyOrientation, BodyVelocity, BodyAngularVelocity, BodyMotion, MemberBody,
                          MemberCore, MemberDilation, CoreVertices, Walls>;
  using Writes = gf::Writes<BodyFrameFiles>;
  // `labels` gives the shapes' names and frames; `layers` per body row.
  BodyFrameOutput(std::filesystem::path out_dir, double interval, BodyFrameLabels labels, std::vector<int> layers);
  std::string_view name() const override { return "body_frame_output"; }
  void run(World& world, const StepContext& now) override;
  void finish(World& world);
  std::size_t frames() const { return times_.size(); }
  void save(CheckpointWriter& out) const override;
  // Frames written after the checkpoint by the stopped run are written again under the same names.
  void restore(const CheckpointReader& in) override;

 private:
  void write(World& world, double t);
  void write_walls(World& world, double t);
  std::filesystem::path dir_;
  FrameSeries vtu_;  // bodies.pvd and bodies/bodies_NNNNNN.vtu (body_vtu.hpp), at the same times
  // walls.pvd (wall_surfaces.hpp): opened at the first frame of a scene with walls.
  std::unique_ptr<FrameSeries> walls_;
  bool walls_checked_ = false;
  SceneBox box_;
  double interval_;
  BodyFrameLabels labels_;
  std::vector<int> layers_;
  std::vector<double> times_;
  double next_ = 0;
};

// The PNG files of a BodyPictureOutput (a tag for the schedule).
struct BodyPictureFiles {};

class BodyPictureOutput : public SystemBase<BodyPictureOutput>, public Checkpointable {
 public:
  using Reads = gf::Reads<BodyPosition, BodyOrientation, BodyMotion, MemberBody, MemberCore, MemberDilation,
                          MemberCentre, CoreVertices>;
  using Writes = gf::Writes<BodyPictureFiles>;
  // colour[i]: body row i's colour; `legend` goes to the PNG's Comment entry.
  // `entries`: the legend band's swatches (picture_legend.hpp), drawn with the time and a scale bar.
  BodyPictureOutput(std::filesystem::path dir, double interval, BodyView view, std::vector<Rgb> colour,
                    std::string legend, std::vector<PictureLegend::Entry> entries = {});
  std::string_view name() const override { return "body_picture_output"; }
  void run(World& world, const StepContext& now) override;
  std::size_t pictures() const { return written_; }
  const std::filesystem::path& last_picture() const { return last_; }
  void save(CheckpointWriter& out) const override;
  void restore(const CheckpointReader& in) override;

 private:
  std::filesystem::path dir_;
  double interval_;
  BodyView view_;
  std::vector<Rgb> colour_;
  std::string legend_;
  std::vector<PictureLegend::Entry> entries_;
  double next_ = 0;
  std::size_t written_ = 0;
  std::filesystem::path last_;
};

}  // namespace gf
