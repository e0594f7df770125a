// The model layer's commands. `grainflow run/check` pick the model from the scene: a scene with a
// top-level [liquid] table is an MPS liquid scene, any other scene is a DEM scene.
#pragma once

#include "engine/cli.hpp"
#include "engine/scene.hpp"

namespace gf {

enum class SceneModel { Dem, Liquid };
SceneModel scene_model(const SceneDoc& doc);

int run_dem_command(const CliOptions& opt);
int check_dem_command(const CliOptions& opt);
int run_liquid_command(const CliOptions& opt);    // systems/mps/liquid_app.cpp
int check_liquid_command(const CliOptions& opt);

}  // namespace gf
