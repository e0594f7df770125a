// A scene with a liquid and grains in it (seed 003's MPS-DEM coupling): a top-level [liquid] table as
// an MPS scene has, grains as a DEM scene has them ([[species]], [contact], [[fill]], [[wall]]), and a
// [coupling] table:
//   substeps          DEM steps per liquid step (run.dt is the liquid's step); when absent or 0, the
//                     fewest that keep dt/k within run.dt_safety of the contact law's smallest period
//   smoothing_radius  m, the radius h over which a grain's volume and force are shared with the nodes
//   drag              "ergun_wen_yu" (the seed's switch at eps = 0.8) or "blend" (Huilin-Gidaspow)
//   min_liquid_fraction  floor of the nodes' liquid fraction (default 0.2)
//   share_with        "all_nodes" (default, the seed's kernel sum over every particle: a grain beside a wall
//                     shares its volume with the wall's nodes and reads their zero velocity) or
//                     "fluid_nodes" (the wall rule: shares renormalised over the fluid nodes within h, so a
//                     grain beside a wall reads and moves only liquid)
//   fixed_grains      true: the grains are held where the fills put them (a fixed bed): they feel the
//                      liquid's force and give the liquid its reaction but never move, and no contact or
//                      integration runs; substeps then defaults to 1 and the contact law sets no limit
//   modified_pressure  true: a closed box filled with liquid solves for the pressure less its hydrostatic
//                      part, without gravity in the liquid's step (exact for one density in a closed box;
//                      the grains keep gravity and buoyancy); the pressure outputs are then that part
//   averaged          true: the liquid is locally averaged (seed 003's model B): its nodes target the
//                      number density eps n0 at their liquid fraction eps (systems/mps/liquid_fraction.hpp),
//                      so the liquid makes room for the grains; default false (the liquid fills the grains'
//                      volume as it fills clear liquid)
// [run] is shared: dt, duration and gravity (required here, both parts feel it) serve both parts; skin,
// seed and max_overlap are the grains', [liquid] and [geometry] the liquid's. Each part's loader reads
// its keys; unknown keys are checked once, over the whole file.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "engine/scene.hpp"
#include "systems/coupling/coupling_settings.hpp"
#include "systems/mps/liquid_scene.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

struct CoupledScene {
  std::filesystem::path file;
  LiquidScene liquid;
  DemScene dem;  // dem.dt is the sub-step, liquid.dt / substeps
  CouplingSpec coupling;
  std::int64_t steps() const { return liquid.steps(); }
};

// A scene with a [liquid] table and grains ([[species]] or [[fill]]).
bool is_coupled_scene(const SceneDoc& doc);

// Both parts and the coupling, every key checked; SceneError naming file, line, key and fix.
CoupledScene load_coupled_scene(const SceneDoc& doc);

const char* drag_model_name(DragModel m);

}  // namespace gf
