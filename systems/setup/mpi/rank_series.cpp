#include "systems/setup/mpi/rank_series.hpp"

#include <array>
#include <limits>
#include <stdexcept>

#include "systems/output/sample_grid.hpp"
#include "engine/mpi/rank_failure.hpp"
#include "systems/analysis/drum_section.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/setup/mpi/gathered_grains.hpp"
#include "systems/setup/mpi/rank_wall_loads.hpp"

namespace gf {

namespace {

std::vector<double> series_values(const SeriesRow& row, const SeriesSettings& s) {
  std::vector<double> v{row.time,
                        row.angle,
                        row.ke_translational,
                        row.ke_rotational,
                        static_cast<double>(row.pair_contacts),
                        static_cast<double>(row.wall_contacts),
                        row.max_overlap_ratio,
                        row.segregation_index};
  if (s.mixing_cell > 0) v.insert(v.end(), {row.lacey_index, row.lacey_cell_grains});
  if (s.pattern)
    v.insert(v.end(), {static_cast<double>(row.pattern), static_cast<double>(row.petals), row.pattern_contrast,
                       row.surface_angle, row.radial_segregation, row.depth_segregation});
  if (s.flow)
    v.insert(v.end(), {static_cast<double>(row.grains), row.holdup_mass, row.fed_mass, row.discharged_mass,
                       row.feed_backlog});
  return v;
}

}  // namespace

RankSeries::RankSeries(SeriesSettings s, const MpiContext& mpi) : s_(std::move(s)), mpi_(&mpi) {
  if (s_.mixing_cell > 0 && s_.segregation_type < 0)
    throw std::logic_error("series: Lacey's index requested without a species to measure (segregation_type)");
  columns_ = series_columns(s_);
  on_every_rank(mpi, [&] {
    if (mpi.rank() != 0 || !s_.csv) return;
    if (s_.resume_rows)
      csv_ = std::make_unique<SeriesCsv>(SeriesCsv::resume(*s_.csv, columns_, *s_.resume_rows));
    else
      csv_ = std::make_unique<SeriesCsv>(*s_.csv, columns_);
    if (s_.wall_names.empty()) return;
    const std::filesystem::path walls = s_.csv->parent_path() / "walls.csv";
    if (s_.resume_rows)
      walls_csv_ = std::make_unique<WallLoadsCsv>(walls, s_.wall_names, s_.analytic_walls,
                                                  WallLoadsCsv::KeepRows{*s_.resume_rows});
    else
      walls_csv_ = std::make_unique<WallLoadsCsv>(walls, s_.wall_names, s_.analytic_walls,
                                                  std::numeric_limits<double>::quiet_NaN());
  });
}

void RankSeries::save(CheckpointWriter& out) const {
  out.value("rank_series.next", next_);
  out.value("rank_series.rows", static_cast<std::uint64_t>(rows_));
  out.value("rank_series.row", row_);
  if (walls_csv_) walls_csv_->save(out);
}

void RankSeries::restore(const CheckpointReader& in) {
  next_ = in.value<double>("rank_series.next");
  rows_ = in.value<std::uint64_t>("rank_series.rows");
  row_ = in.value<SeriesRow>("rank_series.row");
  if (walls_csv_) walls_csv_->restore(in);  // rank 0, from part 0 whatever the rank count
}

void RankSeries::observe(World& w) {
  if (!s_.csv) return;  // no file: only the final row is sampled
  const double t = w.clock.t;
  if (!sample_due(t, next_, w.clock.dt)) return;
  next_ = next_sample(t, next_, s_.interval, w.clock.dt);
  sample(w, t);
}

const SeriesRow& RankSeries::finish(World& w) {
  if (!(row_.valid && row_.time == w.clock.t)) sample(w, w.clock.t);
  return row_;
}

bool RankSeries::needs_all() const { return s_.segregation_type >= 0 || s_.mixing_cell > 0 || s_.pattern; }

void RankSeries::sample(World& w, double t) {
  const MpiContext& mpi = *mpi_;
  const Grains& g = w.grains;
  const Walls& walls = w.resources.get<Walls>();
  const MeshWalls* meshes = w.resources.find<MeshWalls>();
  const Energies e = kinetic_energy(g);
  ContactStats cs = contact_stats(g, w.resources.get<NeighborList>(), walls);
  if (meshes) add_mesh_contacts(cs, g, *meshes, t, walls.rotation_enabled);
  SeriesRow row;
  row.time = t;
  row.angle = rotation_angle(walls, t, meshes);
  row.ke_translational = mpi.sum(e.translational);
  row.ke_rotational = mpi.sum(e.rotational);
  row.pair_contacts = mpi.sum(cs.pair_contacts);
  row.wall_contacts = mpi.sum(cs.wall_contacts);
  row.max_overlap_ratio = mpi.max(cs.max_overlap_ratio);
  if (s_.flow) {  // the feeds' and outlets' state is the same on every rank; the rows are summed
    const FlowState& f = w.resources.get<FlowState>();
    double kg = 0.0;
    for (std::size_t i = 0; i < g.n_owned; ++i) kg += g.mass.m[i];
    row.has_flow = true;
    row.grains = mpi.sum(static_cast<std::int64_t>(g.n_owned));
    row.holdup_mass = mpi.sum(kg);
    row.fed_mass = f.fed_mass();
    row.discharged_mass = f.discharged_mass();
    row.feed_backlog = f.backlog();
  }
  row.has_mixing = s_.mixing_cell > 0;
  row.has_pattern = s_.pattern;
  row.valid = true;
  row_ = row;
  const Grains all = needs_all() ? gather_shapes(g, mpi) : Grains{};
  const bool loads = !s_.wall_names.empty() && s_.csv;  // alike on every rank
  const WallLoads wall_loads = loads ? gather_wall_loads(walls.loads, mpi) : WallLoads{};
  const MeshWallLoads* mine = w.resources.find<MeshWallLoads>();
  const WallLoads mesh_loads = loads && mine ? gather_wall_loads(*mine, mpi) : WallLoads{};
  on_every_rank(mpi, [&] {
    if (mpi.rank() != 0) return;
    if (needs_all()) sample_whole(all, w, row_);
    if (csv_) csv_->append(series_values(row_, s_));
    if (walls_csv_) walls_csv_->write(t, &wall_loads, mine ? &mesh_loads : nullptr);
  });
  ++rows_;
}

// The measures of every grain at once, from the grains gathered on rank 0.
void RankSeries::sample_whole(const Grains& all, World& w, SeriesRow& row) const {
  if (s_.segregation_type >= 0)
    row.segregation_index = segregation_index(all, s_.segregation_type, s_.segregation_cell);
  if (s_.mixing_cell > 0) {
    const LaceyIndex m = lacey_index(all, s_.segregation_type, s_.mixing_cell, s_.mixing_min_grains);
    row.lacey_index = m.index;
    row.lacey_cell_grains = m.grains_per_cell;
    row.lacey_cell = m.cell;
  }
  if (!s_.pattern) return;
  const Walls& walls = w.resources.get<Walls>();
  const auto drum = find_drum(walls);
  if (!drum) throw std::logic_error("series: pattern columns requested for a scene without a drum wall");
  const Gravity& gr = w.resources.get<Gravity>();
  const DrumSection section = drum_section(walls.list[*drum], {gr.x, gr.y, gr.z});
  const std::size_t n = all.n_owned;
  const PatternGrains pg{{all.pos.x.data(), n}, {all.pos.y.data(), n}, {all.pos.z.data(), n},
                         {all.radius.r.data(), n}, {all.species.type.data(), n}};
  const Pattern p = classify_pattern(pg, section, s_.pattern_settings);
  row.pattern = static_cast<int>(p.kind);
  row.petals = p.petals;
  row.pattern_contrast = p.contrast;
  row.ring_lobes = p.ring_lobes;
  row.surface_angle = p.surface_angle;
  row.surface = free_surface({pg.x, pg.y, pg.z, pg.r, {all.vel.x.data(), n}, {all.vel.y.data(), n},
                              {all.vel.z.data(), n}},
                             section);
  row.radial_segregation = radial_segregation(all, s_.segregation_type, section).index;
  row.depth_segregation = depth_segregation(all, s_.segregation_type, section, p.surface_angle, p.surface_level).index;
}

}  // namespace gf
