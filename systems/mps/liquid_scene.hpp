// Loads and checks an MPS liquid scene (a scene with a top-level [liquid] table). Every key is read through the
// checked scene reader; stability limits (CFL with the scene's velocity scale, viscous diffusion number) are
// checked here, before anything runs, like the DEM side checks its time step.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "engine/output_times.hpp"
#include "engine/scene.hpp"
#include "systems/mps/boundaries.hpp"
#include "systems/mps/flow_drive.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/stability.hpp"

namespace gf {

struct LiquidOutput : OutputTimes {};

struct LiquidScene {
  std::filesystem::path file;
  LiquidParams params;
  LiquidGeometry geometry;
  std::vector<FluidBlock> blocks;
  int fluid_line = 0;         // line of the first [[fluid]] table, for messages about the blocks
  double dt = 0;              // s
  double duration = 0;        // s
  double velocity_scale = 0;  // m/s, expected max speed, for the CFL check at load
  double cfl = 0;             // velocity_scale dt / l0
  double diffusion = 0;       // nu dt / l0^2
  double cfl_limit = 0.5, diffusion_limit = 0.2, density_limit = 1.5, domain_margin = 0;
  bool allow_unstable_dt = false;
  LiquidOutput output;
  std::optional<FlowDrive> drive;  // [drive]: the body force along the periodic axis controlled

  std::int64_t steps() const;
  StabilityLimits limits() const;
};

// check_unused_keys off: the caller reads more of the scene (grains beside the liquid) and checks for unknown
// keys itself.
LiquidScene load_liquid_scene(const SceneDoc& doc, bool check_unused_keys = true);

}  // namespace gf
