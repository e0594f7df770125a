// `grainflow check` and `grainflow run` for scenes of composite grains ([[shape]], [[bodies]]): the
// same stages as for grains (validate, prime, settle, run with observers, summary.json), with the
// bodies' outputs (systems/output/body_outputs.hpp, body_picture.hpp) and checkpoints of the
// bodies' state (dem_body_checkpoint.hpp) that --resume continues bit for bit.
#pragma once

#include "engine/cli.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

int check_body_command(const CliOptions& opt, const DemScene& s);
int run_body_command(const CliOptions& opt, const DemScene& s);

}  // namespace gf
