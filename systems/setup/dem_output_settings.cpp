#include "systems/setup/dem_output_settings.hpp"

#include <cstdio>

#include "systems/output/picture_legend.hpp"

namespace gf {

SeriesSettings scene_series_settings(const DemScene& s, const std::filesystem::path& out) {
  SeriesSettings ss;
  if (s.output.series_interval > 0) ss.csv = out / "series.csv";
  ss.interval = s.output.series_interval > 0 ? s.output.series_interval : 1000 * s.dt;
  ss.segregation_type = s.segregation_type;
  ss.segregation_cell = s.segregation_cell;
  ss.pattern = s.pattern;
  ss.pattern_settings.large_type = s.segregation_type;
  ss.mixing_cell = s.mixing_cell;
  ss.mixing_min_grains = s.mixing_min_grains;
  ss.flow = s.flow.any();
  for (const Wall& w : s.walls) ss.wall_names.push_back(w.name);
  ss.analytic_walls = s.walls.size();
  for (const MeshWall& w : s.mesh_walls.list) ss.wall_names.push_back(w.name);
  return ss;
}

bool scene_draws_pictures(const DemScene& s) {
  return !s.output.picture_angles.empty() || s.output.picture_interval > 0;
}

PictureSettings scene_picture_settings(const DemScene& s, const std::filesystem::path& out) {
  PictureSettings ps;
  ps.dir = out / "pictures";
  ps.angles = s.output.picture_angles;
  ps.interval = s.output.picture_interval;
  ps.options = s.output.picture;
  for (std::size_t k = 0; k < s.species.size(); ++k) {
    char hex[16];
    const Rgb& c = ps.options.palette[k];
    std::snprintf(hex, sizeof hex, "#%02X%02X%02X", c[0], c[1], c[2]);
    ps.legend += (k ? ", " : "") + s.species[k].name + " " + hex;
    const SpeciesSpec& sp = s.species[k];
    ps.species_labels.push_back(sp.name + ", " + (sp.size.is_fixed() ? length_label(sp.smallest())
                                                                      : length_label(sp.smallest()) + " to " +
                                                                            length_label(sp.largest())));
  }
  return ps;
}

}  // namespace gf
