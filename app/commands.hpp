// The model layer's commands. `grainflow run/check` pick the model from the scene: a scene with a
// top-level [liquid] table is an MPS liquid scene, one that also holds grains ([[species]], [[fill]] or
// [coupling]) a coupled scene (coupled_scene.hpp), any other scene is a DEM scene.
#pragma once

#include <filesystem>
#include <string>

#include "app/cli.hpp"
#include "engine/scene.hpp"

namespace gf {

enum class SceneModel { Dem, Liquid, Coupled };
SceneModel scene_model(const SceneDoc& doc);

// The end of the message of a run stopped by an output it could not write (a full disk, a file-size
// limit): what is kept, and how to go on (resume from the run's checkpoint, or run again).
std::string write_failure_fix(const CliOptions& opt, const std::filesystem::path& out, bool have_checkpoint);
// The same for a run started by `command` ("grainflow run", "mpiexec -n 4 grainflow_mpi run"), to be
// resumed from `checkpoint` (empty: none was written yet).
std::string write_failure_fix(const std::string& command, const CliOptions& opt, const std::filesystem::path& out,
                              const std::filesystem::path& checkpoint);

int run_dem_command(const CliOptions& opt);
int check_dem_command(const CliOptions& opt);
int run_liquid_command(const CliOptions& opt);    // app/liquid_app.cpp
int check_liquid_command(const CliOptions& opt);
int run_coupled_command(const CliOptions& opt);   // app/coupled_app.cpp
int check_coupled_command(const CliOptions& opt);

}  // namespace gf
