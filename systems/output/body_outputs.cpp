#include "systems/output/body_outputs.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>

#include "systems/output/sample_grid.hpp"
#include "engine/atomic_file.hpp"
#include "systems/output/body_vtu.hpp"

namespace gf {

namespace {


double height(const Gravity& g, double x, double y, double z) {
  const double gn = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
  if (gn == 0.0) return y;  // no gravity: heights along y
  return -(g.x * x + g.y * y + g.z * z) / gn;
}

const char* motion_name(std::uint8_t m) {
  switch (static_cast<Motion>(m)) {
    case Motion::moving: return "moving";
    case Motion::fixed: return "fixed";
    case Motion::removed: return "removed";
  }
  return "unknown";
}

void put(std::string& line, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  line += buf;
}

}  // namespace

BodyEnergies body_kinetic_energy(const Bodies& b) {
  BodyEnergies e;
  for (std::size_t i = 0; i < b.n; ++i) {
    if (!b.moving(i)) continue;
    e.translational += 0.5 * b.mass.m[i] * (b.vel.x[i] * b.vel.x[i] + b.vel.y[i] * b.vel.y[i] + b.vel.z[i] * b.vel.z[i]);
    const Eigen::Quaterniond q(b.q.w[i], b.q.x[i], b.q.y[i], b.q.z[i]);
    const Eigen::Vector3d w = q.conjugate() * Eigen::Vector3d(b.omega.x[i], b.omega.y[i], b.omega.z[i]);
    e.rotational += 0.5 * (b.inertia.i1[i] * w.x() * w.x() + b.inertia.i2[i] * w.y() * w.y() +
                           b.inertia.i3[i] * w.z() * w.z());
  }
  return e;
}

double remaining_fraction(const Bodies& b, const Gravity& g, double h, std::size_t initial) {
  if (initial == 0) return 0.0;
  std::size_t above = 0;
  for (std::size_t i = 0; i < b.n; ++i) above += b.moving(i) && height(g, b.pos.x[i], b.pos.y[i], b.pos.z[i]) > h;
  return static_cast<double>(above) / static_cast<double>(initial);
}

std::vector<int> body_layers(const Bodies& b, const Gravity& g, int layers) {
  std::vector<int> out(b.n, -1);
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < b.n; ++i)
    if (b.moving(i)) rows.push_back(i);
  std::vector<double> h(b.n);
  for (std::size_t i : rows) h[i] = height(g, b.pos.x[i], b.pos.y[i], b.pos.z[i]);
  std::stable_sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t c) { return h[a] < h[c]; });
  for (std::size_t k = 0; k < rows.size(); ++k)
    out[rows[k]] = static_cast<int>(k * static_cast<std::size_t>(layers) / rows.size());
  return out;
}

// ---- Series --------------------------------------------------------------------------------------

BodySeriesOutput::BodySeriesOutput(BodySeriesSettings s) : s_(std::move(s)) {
  if (!s_.csv) return;
  std::vector<std::string> columns{"time",          "ke_translational",  "ke_rotational", "contacts",
                                   "wall_contacts", "max_overlap_ratio", "moving"};
  if (s_.outlet_height) columns.push_back("remaining_fraction");
  if (s_.resume_rows)
    csv_ = std::make_unique<SeriesCsv>(SeriesCsv::resume(*s_.csv, std::move(columns), *s_.resume_rows));
  else
    csv_ = std::make_unique<SeriesCsv>(*s_.csv, std::move(columns));
  if (s_.wall_names.empty()) return;
  const std::filesystem::path walls = s_.csv->parent_path() / "walls.csv";
  const std::size_t n = s_.wall_names.size();
  if (s_.resume_rows)
    walls_csv_ = std::make_unique<WallLoadsCsv>(walls, s_.wall_names, n, WallLoadsCsv::KeepRows{*s_.resume_rows});
  else
    walls_csv_ = std::make_unique<WallLoadsCsv>(walls, s_.wall_names, n, std::numeric_limits<double>::quiet_NaN());
}

void BodySeriesOutput::save(CheckpointWriter& out) const {
  out.value("body_series_output.next", next_);
  out.value("body_series_output.rows", static_cast<std::uint64_t>(rows_));
  if (walls_csv_) walls_csv_->save(out);
}
void BodySeriesOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("body_series_output.next");
  rows_ = in.value<std::uint64_t>("body_series_output.rows");
  if (walls_csv_) walls_csv_->restore(in);
}

void BodySeriesOutput::run(World& world, const StepContext& now) {
  if (!sample_due(now.t, next_, now.dt)) return;
  next_ = next_sample(now.t, next_, s_.interval, now.dt);
  sample(world, now.t);
}

void BodySeriesOutput::finish(World& world) {
  const BodySeriesRow& row = world.resources.get<BodySeriesRow>();
  if (row.valid && row.time == world.clock.t) return;
  sample(world, world.clock.t);
}

void BodySeriesOutput::sample(World& world, double t) {
  const Bodies& b = world.tables.get<Bodies>();
  const BodyContactReport& c = world.resources.get<BodyContactState>().last;
  BodySeriesRow& row = world.resources.get<BodySeriesRow>();
  const BodyEnergies e = body_kinetic_energy(b);
  row.time = t;
  row.ke_translational = e.translational;
  row.ke_rotational = e.rotational;
  row.contacts = static_cast<std::int64_t>(c.pair_contacts - c.fixed_contacts);
  row.wall_contacts = static_cast<std::int64_t>(c.wall_contacts + c.fixed_contacts);
  row.max_overlap_ratio = c.max_overlap / s_.overlap_scale;
  row.moving = 0;
  for (std::size_t i = 0; i < b.n; ++i) row.moving += b.moving(i);
  if (s_.outlet_height)
    row.remaining_fraction = remaining_fraction(b, world.resources.get<Gravity>(), *s_.outlet_height, s_.initial_moving);
  row.valid = true;
  if (!csv_) return;
  std::vector<double> v{row.time,
                        row.ke_translational,
                        row.ke_rotational,
                        static_cast<double>(row.contacts),
                        static_cast<double>(row.wall_contacts),
                        row.max_overlap_ratio,
                        static_cast<double>(row.moving)};
  if (s_.outlet_height) v.push_back(row.remaining_fraction);
  csv_->append(v);
  if (walls_csv_) walls_csv_->write(t, &world.resources.get<BodyContactState>().loads, nullptr);
  ++rows_;
}

// ---- Frames --------------------------------------------------------------------------------------

BodyFrameOutput::BodyFrameOutput(std::filesystem::path out_dir, double interval, BodyFrameLabels labels,
                                 std::vector<int> layers)
    : dir_(out_dir / "frames"),
      vtu_(out_dir, "bodies", "bodies", false, ".vtu"),
      interval_(interval),
      labels_(std::move(labels)),
      layers_(std::move(layers)) {
  ensure_directory(dir_);
}

void BodyFrameOutput::save(CheckpointWriter& out) const {
  out.value("body_frame_output.next", next_);
  out.vector("body_frame_output.times", times_);
}
void BodyFrameOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("body_frame_output.next");
  in.vector("body_frame_output.times", times_);
  vtu_.resume(times_);
}

void BodyFrameOutput::run(World& world, const StepContext& now) {
  if (!sample_due(now.t, next_, now.dt)) return;
  next_ = next_sample(now.t, next_, interval_, now.dt);
  write(world, now.t);
}

void BodyFrameOutput::finish(World& world) {
  if (!times_.empty() && times_.back() == world.clock.t) return;
  write(world, world.clock.t);
}

// The walls at the frame's time, beside the bodies (one file when none moves).
void BodyFrameOutput::write_walls(World& world, double t) {
  const Walls* walls = world.resources.find<Walls>();
  if (!walls_checked_) {
    walls_checked_ = true;
    if (walls == nullptr || walls->list.empty()) return;
    const Bodies& b = world.tables.get<Bodies>();
    std::vector<Vec3d> centres(b.n);
    for (std::size_t i = 0; i < b.n; ++i) centres[i] = {b.pos.x[i], b.pos.y[i], b.pos.z[i]};
    box_ = scene_box(centres, *walls, nullptr);
    walls_ = std::make_unique<FrameSeries>(dir_.parent_path(), "walls", "walls", !walls_move(*walls, nullptr));
    if (times_.size() > 0) walls_->resume(times_);
  }
  if (walls_) walls_->write_with(t, [&] { return wall_surface_vtp(wall_surface(*walls, nullptr, t, box_)); });
}

void BodyFrameOutput::write(World& world, double t) {
  const Bodies& b = world.tables.get<Bodies>();
  vtu_.write_with(t, [&] { return body_vtu_bytes(b, world.tables.get<Members>(), labels_.shape, labels_.group); });
  write_walls(world, t);
  char name[32];
  std::snprintf(name, sizeof name, "frame_%06zu.csv", times_.size());
  std::string text = "id,shape,group,layer,motion,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz\n";
  text.reserve(b.n * 260);
  for (std::size_t i = 0; i < b.n; ++i) {
    const std::size_t shape = labels_.shape[i];
    // The body frame is the shape's principal frame: q_body = q_shape * quaternion(axes).
    Eigen::Quaterniond qs = Eigen::Quaterniond(b.q.w[i], b.q.x[i], b.q.y[i], b.q.z[i]) *
                            labels_.shape_axes[shape].conjugate();
    qs.normalize();
    if (qs.w() < 0) qs.coeffs() *= -1.0;  // one of the two signs, for readable files
    text += std::to_string(i) + "," + labels_.shape_name[shape] + "," + std::to_string(labels_.group[i]) + "," +
            std::to_string(i < layers_.size() ? layers_[i] : -1) + "," + motion_name(b.motion.state[i]);
    for (double v : {b.pos.x[i], b.pos.y[i], b.pos.z[i], qs.w(), qs.x(), qs.y(), qs.z(), b.vel.x[i], b.vel.y[i],
                     b.vel.z[i], b.omega.x[i], b.omega.y[i], b.omega.z[i]}) {
      text += ",";
      put(text, v);
    }
    text += "\n";
  }
  write_file_atomic(dir_ / name, text);
  times_.push_back(t);
  std::string index = "frame,time,file\n";
  for (std::size_t k = 0; k < times_.size(); ++k) {
    std::snprintf(name, sizeof name, "frame_%06zu.csv", k);
    index += std::to_string(k) + ",";
    put(index, times_[k]);
    index += std::string(",") + name + "\n";
  }
  write_file_atomic(dir_ / "frames.csv", index);
}

// ---- Pictures ------------------------------------------------------------------------------------

BodyPictureOutput::BodyPictureOutput(std::filesystem::path dir, double interval, BodyView view, std::vector<Rgb> colour,
                                     std::string legend, std::vector<PictureLegend::Entry> entries)
    : dir_(std::move(dir)),
      interval_(interval),
      view_(view),
      colour_(std::move(colour)),
      legend_(std::move(legend)),
      entries_(std::move(entries)) {
  ensure_directory(dir_);
}

void BodyPictureOutput::save(CheckpointWriter& out) const {
  out.value("body_picture_output.next", next_);
  out.value("body_picture_output.written", static_cast<std::uint64_t>(written_));
}
void BodyPictureOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("body_picture_output.next");
  written_ = in.value<std::uint64_t>("body_picture_output.written");
}

void BodyPictureOutput::run(World& world, const StepContext& now) {
  if (!sample_due(now.t, next_, now.dt)) return;
  const double target = next_;
  next_ = next_sample(now.t, next_, interval_, now.dt);
  PictureLegend band;
  band.time = now.t;
  band.entries = entries_;
  band.px_per_m = view_.size / std::max(view_.hi[view_.right] - view_.lo[view_.right], view_.hi[view_.up] - view_.lo[view_.up]);
  const Image img =
      annotate_picture(render_body_picture(world.tables.get<Bodies>(), world.tables.get<Members>(), colour_, view_), band);
  last_ = dir_ / body_picture_name(target);
  char when[64];
  std::snprintf(when, sizeof when, "t = %.6g s", now.t);
  write_png(last_, img,
            {{"Comment", std::string("side view of the bodies at ") + when + "; colours: " + legend_},
             {"Software", "grainflow"}});
  ++written_;
}

}  // namespace gf
