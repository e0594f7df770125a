#include "systems/output/dem_observers.hpp"

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "systems/output/sample_grid.hpp"
#include "engine/atomic_file.hpp"

namespace gf {

// Rotation angle (rad) of the first rotating wall at time t, else of the first rotating mesh wall
// (omega t while rotation is on, as the mesh contacts place it); 0 if none rotates.
double rotation_angle(const Walls& walls, double t, const MeshWalls* meshes) {
  for (std::size_t w = 0; w < walls.list.size(); ++w)
    if (walls.list[w].omega != 0.0) return walls.angle(w, t);
  if (meshes != nullptr && walls.rotation_enabled)
    for (const MeshWall& m : meshes->list)
      if (m.omega != 0.0) return m.omega * t;
  return 0.0;
}


std::vector<std::string> series_columns(const SeriesSettings& s) {
  std::vector<std::string> c{"time",     "angle",         "ke_translational",  "ke_rotational",
                             "contacts", "wall_contacts", "max_overlap_ratio", "segregation_index"};
  if (s.mixing_cell > 0) c.insert(c.end(), {"lacey_index", "lacey_cell_grains"});
  if (s.pattern)
    c.insert(c.end(), {"pattern", "petals", "pattern_contrast", "surface_angle", "radial_segregation",
                       "depth_segregation"});
  if (s.flow) c.insert(c.end(), {"grains", "holdup_mass", "fed_mass", "discharged_mass", "feed_backlog"});
  return c;
}

std::vector<std::string> surface_columns() {
  return {"time", "angle", "surface_angle", "surface_level", "surface_bulge", "surface_span", "surface_speed",
          "surface_grains"};
}

SeriesOutput::SeriesOutput(SeriesSettings s) : s_(std::move(s)) {
  if (mixing() && s_.segregation_type < 0)
    throw std::logic_error("series: Lacey's index requested without a species to measure (segregation_type)");
  if (!s_.csv) return;
  std::vector<std::string> columns = series_columns(s_);
  if (s_.resume_rows)
    csv_ = std::make_unique<SeriesCsv>(SeriesCsv::resume(*s_.csv, std::move(columns), *s_.resume_rows));
  else
    csv_ = std::make_unique<SeriesCsv>(*s_.csv, std::move(columns));
  if (s_.pattern && !s_.resume_rows)
    surface_csv_ = std::make_unique<SeriesCsv>(s_.csv->parent_path() / "surface.csv", surface_columns());
  if (!s_.wall_names.empty() && !s_.resume_rows)
    walls_csv_ = std::make_unique<WallLoadsCsv>(s_.csv->parent_path() / "walls.csv", s_.wall_names, s_.analytic_walls,
                                                std::numeric_limits<double>::quiet_NaN());
}

void SeriesOutput::save(CheckpointWriter& out) const {
  out.value("series_output.next", next_);
  out.value("series_output.rows", static_cast<std::uint64_t>(rows_));
  if (walls_csv_) walls_csv_->save(out);
}
void SeriesOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("series_output.next");
  rows_ = in.value<std::uint64_t>("series_output.rows");
  if (!s_.csv || (!s_.pattern && s_.wall_names.empty())) return;
  // Their rows are those of series.csv kept by the checkpoint: those before its clock, and the row at
  // its clock when that was a sampled step (a final row off the grid is dropped, as series.csv's is).
  // A run that wrote no surface.csv or walls.csv (an older build) starts one here.
  const double t = s_.resume_time;
  if (!std::isfinite(t)) throw std::logic_error("series: resuming surface.csv without the checkpoint's time");
  const double last = sampled_at(t, in.value<double>("clock.dt")) ? t : std::nextafter(t, -INFINITY);
  if (s_.pattern)
    surface_csv_ = std::make_unique<SeriesCsv>(
        SeriesCsv::resume_through(s_.csv->parent_path() / "surface.csv", surface_columns(), last));
  if (s_.wall_names.empty()) return;
  walls_csv_ = std::make_unique<WallLoadsCsv>(s_.csv->parent_path() / "walls.csv", s_.wall_names, s_.analytic_walls,
                                              last);
  walls_csv_->restore(in);
}

// The grid time sampled last is next_ - interval; the step at t sampled it when it is the first
// step at or past it.
bool SeriesOutput::sampled_at(double t, double dt) const {
  const double g = next_ - s_.interval;
  return sample_due(t, g, dt) && !sample_due(t - dt, g, dt);
}

bool SeriesOutput::samples(const World&, const StepContext& now) const { return sample_due(now.t, next_, now.dt); }

void SeriesOutput::run(World& world, const StepContext& now) {
  const double t = now.t;
  if (!sample_due(t, next_, now.dt)) return;
  next_ = next_sample(t, next_, s_.interval, now.dt);
  sample(world, t);
}

void SeriesOutput::finish(World& world) {
  const SeriesRow& row = world.resources.get<SeriesRow>();
  if (row.valid && row.time == world.clock.t) return;
  // A resumed run that took no step: the checkpoint's sampled row is already the last one kept.
  if (!row.valid && world.clock.t == s_.resume_time && sampled_at(world.clock.t, world.clock.dt)) return;
  sample(world, world.clock.t);
}

void SeriesOutput::sample(World& world, double t) {
  const Grains& g = world.grains;
  const Walls& walls = world.resources.get<Walls>();
  SeriesRow& row = world.resources.get<SeriesRow>();
  const Energies e = kinetic_energy(g);
  ContactStats cs = contact_stats(g, world.resources.get<NeighborList>(), walls);
  if (const MeshWalls* meshes = world.resources.find<MeshWalls>())
    add_mesh_contacts(cs, g, *meshes, t, walls.rotation_enabled);
  row.time = t;
  row.angle = rotation_angle(walls, t, world.resources.find<MeshWalls>());
  row.ke_translational = e.translational;
  row.ke_rotational = e.rotational;
  row.pair_contacts = cs.pair_contacts;
  row.wall_contacts = cs.wall_contacts;
  row.max_overlap_ratio = cs.max_overlap_ratio;
  row.segregation_index =
      s_.segregation_type >= 0 ? segregation_index(g, s_.segregation_type, s_.segregation_cell) : 0.0;
  if (mixing()) sample_mixing(g, row);
  if (s_.pattern) sample_pattern(world, row);
  if (s_.flow) sample_flow(world, row);
  row.valid = true;
  if (csv_) write(row);
  if (walls_csv_) walls_csv_->write(t, &walls.loads, world.resources.find<MeshWallLoads>());
}

void SeriesOutput::sample_mixing(const Grains& g, SeriesRow& row) const {
  const LaceyIndex m = lacey_index(g, s_.segregation_type, s_.mixing_cell, s_.mixing_min_grains);
  row.has_mixing = true;
  row.lacey_index = m.index;
  row.lacey_cell_grains = m.grains_per_cell;
  row.lacey_cell = m.cell;
}

void SeriesOutput::sample_pattern(World& world, SeriesRow& row) const {
  const Grains& g = world.grains;
  const Walls& walls = world.resources.get<Walls>();
  const auto drum = find_drum(walls);
  if (!drum) throw std::logic_error("series: pattern columns requested for a scene without a drum wall");
  const Gravity& gr = world.resources.get<Gravity>();
  const DrumSection section = drum_section(walls.list[*drum], {gr.x, gr.y, gr.z});
  const std::size_t n = g.n_owned;
  const PatternGrains pg{{g.pos.x.data(), n}, {g.pos.y.data(), n}, {g.pos.z.data(), n},
                         {g.radius.r.data(), n}, {g.species.type.data(), n}};
  const Pattern p = classify_pattern(pg, section, s_.pattern_settings);
  row.has_pattern = true;
  row.pattern = static_cast<int>(p.kind);
  row.petals = p.petals;
  row.pattern_contrast = p.contrast;
  row.ring_lobes = p.ring_lobes;
  row.surface_angle = p.surface_angle;
  row.surface = free_surface({pg.x, pg.y, pg.z, pg.r, {g.vel.x.data(), n}, {g.vel.y.data(), n}, {g.vel.z.data(), n}},
                             section);
  row.radial_segregation = radial_segregation(g, s_.segregation_type, section).index;
  row.depth_segregation =
      depth_segregation(g, s_.segregation_type, section, p.surface_angle, p.surface_level).index;
}

void SeriesOutput::sample_flow(World& world, SeriesRow& row) {
  const Grains& g = world.grains;
  const FlowState& f = world.resources.get<FlowState>();
  double kg = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) kg += g.mass.m[i];
  row.has_flow = true;
  row.grains = static_cast<std::int64_t>(g.n_owned);
  row.holdup_mass = kg;
  row.fed_mass = f.fed_mass();
  row.discharged_mass = f.discharged_mass();
  row.feed_backlog = f.backlog();
}

// One csv row in the order of the constructor's columns.
void SeriesOutput::write(const SeriesRow& row) {
  std::array<double, 24> v{};
  std::size_t k = 0;
  for (const double x : {row.time, row.angle, row.ke_translational, row.ke_rotational,
                         static_cast<double>(row.pair_contacts), static_cast<double>(row.wall_contacts),
                         row.max_overlap_ratio, row.segregation_index})
    v[k++] = x;
  if (mixing())
    for (const double x : {row.lacey_index, row.lacey_cell_grains}) v[k++] = x;
  if (s_.pattern)
    for (const double x : {static_cast<double>(row.pattern), static_cast<double>(row.petals), row.pattern_contrast,
                           row.surface_angle, row.radial_segregation, row.depth_segregation})
      v[k++] = x;
  if (s_.flow)
    for (const double x : {static_cast<double>(row.grains), row.holdup_mass, row.fed_mass, row.discharged_mass,
                           row.feed_backlog})
      v[k++] = x;
  csv_->append(std::span<const double>(v.data(), k));
  ++rows_;
  if (!surface_csv_) return;
  const FreeSurface& f = row.surface;
  const std::array<double, 8> w{row.time, row.angle, f.angle,  f.level,
                                f.bulge,  f.span,    f.speed,  static_cast<double>(f.layer_grains)};
  surface_csv_->append(w);
}

FrameOutput::FrameOutput(std::filesystem::path dir, double interval, FrameFields fields, std::string key)
    : series_(std::move(dir)), interval_(interval), fields_(fields), key_(std::move(key)) {}

void FrameOutput::save(CheckpointWriter& out) const {
  out.value(key_ + ".next", next_);
  out.value(key_ + ".last_written", last_written_);
  out.vector(key_ + ".times", series_.times());
}

void FrameOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>(key_ + ".next");
  last_written_ = in.value<double>(key_ + ".last_written");
  std::vector<double> times;
  in.vector(key_ + ".times", times);
  series_.resume(times);
  resumed_times_ = times;
}

void FrameOutput::write(World& world, double t) {
  series_.write(world.grains, t, fields_);
  last_written_ = t;
  static const Walls kNone;
  const Walls* found = world.resources.find<Walls>();
  const Walls& walls = found ? *found : kNone;
  const MeshWalls* meshes = world.resources.find<MeshWalls>();
  if (!walls_checked_) {
    walls_checked_ = true;
    if (walls.list.empty() && (meshes == nullptr || meshes->list.empty())) return;
    box_ = scene_box(world.grains, walls, meshes);
    walls_ = std::make_unique<FrameSeries>(series_.pvd_path().parent_path(), "walls", "walls",
                                           !walls_move(walls, meshes));
    if (!resumed_times_.empty()) walls_->resume(resumed_times_);
  }
  if (walls_) walls_->write_with(t, [&] { return wall_surface_vtp(wall_surface(walls, meshes, t, box_)); });
}

bool FrameOutput::samples(const World&, const StepContext& now) const { return sample_due(now.t, next_, now.dt); }

void FrameOutput::run(World& world, const StepContext& now) {
  const double t = now.t;
  if (!sample_due(t, next_, now.dt)) return;
  next_ = next_sample(t, next_, interval_, now.dt);
  write(world, t);
}

void FrameOutput::finish(World& world) {
  if (world.clock.t == last_written_) return;
  write(world, world.clock.t);
}

PictureOutput::PictureOutput(PictureSettings s) : s_(std::move(s)) {}

void PictureOutput::save(CheckpointWriter& out) const {
  out.value("picture_output.next_angle", static_cast<std::uint64_t>(next_angle_));
  out.value("picture_output.next_multiple", next_multiple_);
  out.value("picture_output.written", static_cast<std::uint64_t>(written_));
}

void PictureOutput::restore(const CheckpointReader& in) {
  next_angle_ = in.value<std::uint64_t>("picture_output.next_angle");
  next_multiple_ = in.value<std::int64_t>("picture_output.next_multiple");
  written_ = in.value<std::uint64_t>("picture_output.written");
}

double PictureOutput::next_target() const {
  double t = std::numeric_limits<double>::infinity();
  if (next_angle_ < s_.angles.size()) t = s_.angles[next_angle_];
  if (s_.interval > 0) t = std::min(t, static_cast<double>(next_multiple_) * s_.interval);
  return t;
}

bool PictureOutput::samples(const World& world, const StepContext& now) const {
  return due(world.resources.get<Walls>(), now).has_value();
}

void PictureOutput::run(World& world, const StepContext& now) {
  const Walls& walls = world.resources.get<Walls>();
  if (const auto angle = due(walls, now)) draw(world.grains, walls, world.resources.get<Gravity>(), now, *angle);
}

std::optional<double> PictureOutput::due(const Walls& walls, const StepContext& now) const {
  double omega = 0;
  for (const Wall& w : walls.list)
    if (w.omega != 0.0) {
      omega = w.omega;
      break;
    }
  // Reached up to round-off of the clock, as the time-based observers are.
  const double angle = std::abs(rotation_angle(walls, now.t)) + 1e-6 * std::abs(omega) * now.dt;
  if (next_target() > angle) return std::nullopt;
  return angle;
}

PictureLegend PictureOutput::legend(const Walls& walls, std::size_t drum, const DrumSection& section, double t) const {
  PictureLegend l;
  l.time = t;
  l.angle = rotation_angle(walls, t);
  const Wall& w = walls.list[drum];
  const double spin = w.omega * dot(w.rot_axis, section.axis);  // about the axis pointing at the viewer
  l.omega = std::abs(w.omega);
  l.turning = spin > 0.0 ? 1 : (spin < 0.0 ? -1 : 0);
  l.px_per_m = picture_scale(section, s_.options.size).px_per_m;
  if (s_.options.colour == PictureOptions::Colour::Speed) {
    l.bar_max = s_.options.speed_max;
    l.bar_unit = "m/s (speed)";
  } else {
    for (std::size_t k = 0; k < s_.species_labels.size() && k < s_.options.palette.size(); ++k)
      l.entries.push_back({s_.species_labels[k], s_.options.palette[k]});
  }
  return l;
}

void PictureOutput::draw(const Grains& g, const Walls& walls, const Gravity& gr, const StepContext& now, double angle,
                         bool write) {
  if (!write) {
    for (double target = next_target(); target <= angle; target = next_target()) pass(target);
    return;
  }
  const double t = now.t;
  const auto drum = find_drum(walls);
  if (!drum) throw std::logic_error("pictures requested for a scene without a drum wall");
  const std::size_t n = g.n_owned;
  PictureGrains pg{{g.pos.x.data(), n}, {g.pos.y.data(), n}, {g.pos.z.data(), n}, {g.radius.r.data(), n},
                   {g.species.type.data(), n}, {}};
  if (s_.options.colour == PictureOptions::Colour::Speed) {
    speed_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      speed_[i] = std::sqrt(g.vel.x[i] * g.vel.x[i] + g.vel.y[i] * g.vel.y[i] + g.vel.z[i] * g.vel.z[i]);
    pg.speed = speed_;
  }
  const DrumSection section = drum_section(walls.list[*drum], {gr.x, gr.y, gr.z});
  const Image img = annotate_picture(render_drum_picture(pg, section, s_.options), legend(walls, *drum, section, t));
  ensure_directory(s_.dir);
  char title[160];
  std::snprintf(title, sizeof title,
                "drum cross-section at rotation angle %.6g rad (t = %.6g s), viewed along the axis",
                rotation_angle(walls, t), t);
  std::string comment = s_.options.colour == PictureOptions::Colour::Speed
                            ? "colour: speed, viridis from 0 to " + std::to_string(s_.options.speed_max) + " m/s"
                            : "colour: species, " + s_.legend;
  // Every target reached by this step gets its file (more than one only if targets are closer than omega dt).
  for (double target = next_target(); target <= angle; target = next_target()) {
    last_ = s_.dir / picture_name(target);
    write_png(last_, img, {{"Title", title}, {"Comment", comment}, {"Software", "grainflow"}});
    pass(target);
  }
}

void PictureOutput::pass(double target) {
  ++written_;
  if (next_angle_ < s_.angles.size() && s_.angles[next_angle_] == target) ++next_angle_;
  if (s_.interval > 0 && static_cast<double>(next_multiple_) * s_.interval == target) ++next_multiple_;
}

}  // namespace gf
