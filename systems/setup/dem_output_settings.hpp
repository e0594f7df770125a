// A grain scene's [output] and [analysis] read into the settings of its observers
// (systems/output/dem_observers.hpp), which know no scene.
#pragma once

#include <filesystem>

#include "systems/output/dem_observers.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// The settings `grainflow run` gives its SeriesOutput for a scene (the csv under out, if any).
SeriesSettings scene_series_settings(const DemScene& s, const std::filesystem::path& out);

// Whether the scene asks for drum pictures (output.picture_angles or output.picture_interval), and
// the settings it gives them, into out/pictures.
bool scene_draws_pictures(const DemScene& s);
PictureSettings scene_picture_settings(const DemScene& s, const std::filesystem::path& out);

}  // namespace gf
