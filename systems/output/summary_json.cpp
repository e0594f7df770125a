#include "systems/output/summary_json.hpp"

#include <cmath>

#include <nlohmann/json.hpp>

#include "engine/atomic_file.hpp"
#include "systems/output/dem_observers.hpp"

namespace gf {

void write_summary_json(const std::filesystem::path& file, const nlohmann::json& doc) {
  // Invalid UTF-8 (a scene name from a Latin-1 file, say) is replaced rather than thrown on:
  // losing a whole run's summary over one byte in one string is the worse outcome.
  std::string text = doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  text += '\n';
  write_file_atomic(file, text);
}

nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json final_row_json(const SeriesRow& row) {
  nlohmann::json j = {{"time", row.time},
                      {"angle", row.angle},
                      {"ke_translational", row.ke_translational},
                      {"ke_rotational", row.ke_rotational},
                      {"contacts", row.pair_contacts},
                      {"wall_contacts", row.wall_contacts},
                      {"max_overlap_ratio", row.max_overlap_ratio},
                      {"segregation_index", row.segregation_index}};
  if (row.has_mixing) {
    j["lacey_index"] = number_or_null(row.lacey_index);
    j["lacey_cell"] = row.lacey_cell;
    j["lacey_cell_grains"] = row.lacey_cell_grains;
  }
  if (row.has_pattern) {
    static const char* kinds[] = {"undecided", "moon", "petals"};
    j["pattern"] = kinds[row.pattern + 1];
    j["petals"] = row.petals;
    j["pattern_contrast"] = row.pattern_contrast;
    j["surface_angle"] = number_or_null(row.surface_angle);  // no surface to fit: null
    j["surface_bulge"] = number_or_null(row.surface.bulge);
    j["surface_speed"] = number_or_null(row.surface.speed);
    j["ring_radii"] = kRingRadii;      // of the drum radius
    j["ring_lobes"] = row.ring_lobes;  // lobes crossing each ring, -1 undefined
    j["radial_segregation"] = number_or_null(row.radial_segregation);
    j["depth_segregation"] = number_or_null(row.depth_segregation);
  }
  return j;
}

}  // namespace gf
