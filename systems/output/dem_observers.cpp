#include "systems/output/dem_observers.hpp"

#include <array>
#include <cstdio>
#include <string>

namespace gf {

namespace {
// Due at t >= next, up to round-off of the clock (t = k dt).
bool due(double t, double next, double dt) { return t >= next - 1e-6 * dt; }
// Sampling times stay on the grid k * interval even when the interval is not a multiple of dt.
double next_sample(double t, double next, double interval, double dt) {
  while (due(t, next, dt)) next += interval;
  return next;
}
}  // namespace

SeriesOutput::SeriesOutput(SeriesSettings s) : s_(std::move(s)) {
  if (!s_.csv) return;
  std::vector<std::string> columns{"time",           "angle",         "ke_translational",  "ke_rotational",
                                   "contacts",       "wall_contacts", "max_overlap_ratio", "segregation_index"};
  if (s_.resume_rows)
    csv_ = std::make_unique<SeriesCsv>(SeriesCsv::resume(*s_.csv, std::move(columns), *s_.resume_rows));
  else
    csv_ = std::make_unique<SeriesCsv>(*s_.csv, std::move(columns));
}

void SeriesOutput::save(CheckpointWriter& out) const {
  out.value("series_output.next", next_);
  out.value("series_output.rows", static_cast<std::uint64_t>(rows_));
}
void SeriesOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("series_output.next");
  rows_ = in.value<std::uint64_t>("series_output.rows");
}

void SeriesOutput::run(World& world) {
  const double t = world.clock.t;
  if (!due(t, next_, world.clock.dt)) return;
  next_ = next_sample(t, next_, s_.interval, world.clock.dt);
  sample(world);
}

void SeriesOutput::finish(World& world) {
  const SeriesRow& row = world.resources.get<SeriesRow>();
  if (row.valid && row.time == world.clock.t) return;
  sample(world);
}

void SeriesOutput::sample(World& world) {
  const double t = world.clock.t;
  const Grains& g = world.grains;
  const Walls& walls = world.resources.get<Walls>();
  SeriesRow& row = world.resources.get<SeriesRow>();
  const Energies e = kinetic_energy(g);
  const ContactStats cs = contact_stats(g, world.resources.get<NeighborList>(), walls);
  row.time = t;
  row.angle = 0;
  for (std::size_t w = 0; w < walls.list.size(); ++w)
    if (walls.list[w].omega != 0.0) {
      row.angle = walls.angle(w, t);
      break;
    }
  row.ke_translational = e.translational;
  row.ke_rotational = e.rotational;
  row.pair_contacts = cs.pair_contacts;
  row.wall_contacts = cs.wall_contacts;
  row.max_overlap_ratio = cs.max_overlap_ratio;
  row.segregation_index =
      s_.segregation_type >= 0 ? segregation_index(g, s_.segregation_type, s_.segregation_cell) : 0.0;
  row.valid = true;
  if (csv_) {
    const std::array<double, 8> v{row.time,
                                  row.angle,
                                  row.ke_translational,
                                  row.ke_rotational,
                                  static_cast<double>(row.pair_contacts),
                                  static_cast<double>(row.wall_contacts),
                                  row.max_overlap_ratio,
                                  row.segregation_index};
    csv_->append(v);
    ++rows_;
  }
  char buf[256];
  if (!cs.finite || !std::isfinite(e.translational) || !std::isfinite(e.rotational)) {
    std::snprintf(buf, sizeof buf, "at t = %.6g s a position or velocity is not finite", t);
    throw StabilityError(std::string(buf) +
                         ": the run blew up. Fix: reduce run.dt (see the critical step from `grainflow check`)");
  }
  if (cs.max_overlap_ratio > s_.max_overlap) {
    std::snprintf(buf, sizeof buf, "at t = %.6g s an overlap reached %.3g of the smaller diameter (limit %.3g)", t,
                  cs.max_overlap_ratio, s_.max_overlap);
    throw StabilityError(std::string(buf) +
                         ". Fix: reduce run.dt, raise the stiffness kn, or raise run.max_overlap if such overlaps "
                         "are intended");
  }
}

FrameOutput::FrameOutput(std::filesystem::path dir, double interval, FrameFields fields)
    : series_(std::move(dir)), interval_(interval), fields_(fields) {}

void FrameOutput::save(CheckpointWriter& out) const {
  out.value("frame_output.next", next_);
  out.value("frame_output.last_written", last_written_);
  out.vector("frame_output.times", series_.times());
}

void FrameOutput::restore(const CheckpointReader& in) {
  next_ = in.value<double>("frame_output.next");
  last_written_ = in.value<double>("frame_output.last_written");
  std::vector<double> times;
  in.vector("frame_output.times", times);
  series_.resume(times);
}

void FrameOutput::run(World& world) {
  const double t = world.clock.t;
  if (!due(t, next_, world.clock.dt)) return;
  next_ = next_sample(t, next_, interval_, world.clock.dt);
  series_.write(world.grains, t, fields_);
  last_written_ = t;
}

void FrameOutput::finish(World& world) {
  if (world.clock.t == last_written_) return;
  series_.write(world.grains, world.clock.t, fields_);
  last_written_ = world.clock.t;
}

}  // namespace gf
