// final_state.csv: every owned grain's id, type, diameter, position, velocity and spin, in id order (the
// portable state a `kind = "file"` fill reads back; systems/fill/state_csv.hpp).
#pragma once

#include <filesystem>

#include "engine/grains.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

void write_final_state(const std::filesystem::path& file, const Grains& g);

}  // namespace gf
