// `grainflow check` and `grainflow run` for scenes of composite grains ([[shape]], [[bodies]]): the
// same stages as for grains (validate, prime, settle, run with observers, summary.json), with the
// bodies' outputs (systems/output/body_outputs.hpp, body_picture.hpp) and checkpoints of the
// bodies' state (dem_body_checkpoint.hpp) that --resume continues bit for bit.
#pragma once

#include <functional>
#include <string>

#include "app/cli.hpp"
#include "engine/world.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

int check_body_command(const CliOptions& opt, const DemScene& s);
// A run shared by several processes that step one state together (grainflow_mpi): what each
// process adds to the world before the first step (the contacts' split, body_contact_split.hpp), how
// a setup phase's failure on one process stops them all, and whether this process writes the
// outputs. The others step alike and write nothing.
struct BodyRunHooks {
  std::function<void(World&)> install;
  // Runs a setup phase (which calls no collective) on this process and shares its outcome: a
  // failure on any process throws on every one. None: the phase runs alone.
  std::function<void(const std::function<void()>&)> together;
  bool writer = true;
  int ranks = 1;
  std::string program = "grainflow";  // the name the lines it prints start with
  std::string scene_json;              // the scene as read, for summary.json (SceneDoc::resolved_json)
};

int run_body_command(const CliOptions& opt, const DemScene& s, const BodyRunHooks& hooks = {});

}  // namespace gf
