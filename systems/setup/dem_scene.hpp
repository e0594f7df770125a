// A dry soft-sphere DEM scene: the validated model read from a scene file, and the world and
// schedules built from it. Only the systems the scene needs are scheduled.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "engine/output_times.hpp"
#include "engine/scene.hpp"
#include "engine/schedule.hpp"
#include "engine/world.hpp"
#include "systems/contact/contact_table.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/fill/region.hpp"
#include "systems/fill/size_distribution.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/integrate/force_terms.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/output/drum_picture.hpp"
#include "systems/output/layer_output.hpp"
#include "systems/output/vtk_frames.hpp"
#include "systems/periodic/periodic_images.hpp"
#include "systems/setup/dem_body_scene.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

struct SpeciesSpec {
  std::string name;
  SizeDistribution size;  // each grain's diameter (m): one value or a distribution
  double density = 0;   // kg/m^3
  double mass = 0;      // kg: of a grain of the smallest diameter (the only one for a fixed size)
  double inertia = 0;   // kg m^2 (solid sphere), of the same grain
  bool rotates = true;  // false: the grains only translate (their torques are not integrated)

  double smallest() const { return size.smallest(); }  // m
  double largest() const { return size.largest(); }    // m
  // m: the number-mean diameter (a fixed size's own), which orders species and scales their cells.
  double mean_diameter() const { return size.is_fixed() ? size.value : size.mean_diameter(); }
  // A grain of radius r: its mass and inverse moment of inertia (0 when the species does not rotate).
  // A fixed size's grains take the species' own values, bit for bit.
  double grain_mass(double r) const;
  double grain_inv_inertia(double r) const;
};

struct FillSpec {
  enum class Kind { Random, File } kind = Kind::Random;
  int line = 0;
  std::string where;  // "fill[0]" for messages
  // random
  Region region;
  std::vector<std::pair<std::int32_t, std::size_t>> counts;  // species index, count
  std::uint64_t seed = 0;
  // file
  std::filesystem::path path;
  std::vector<std::pair<std::int32_t, std::int32_t>> type_map;  // csv type -> species index
};

struct OutputSpec : OutputTimes {
  FrameFields fields;
  // Drum pictures at these rotation angles (rad of the first rotating wall), and every
  // picture_interval (rad, 0 = none); sorted, without duplicates.
  std::vector<double> picture_angles;
  double picture_interval = 0;
  PictureOptions picture;  // palette filled from the species' diameters
};

struct DemScene {
  std::filesystem::path file;
  double dt = 0;              // s
  double dt_safety = 0.1;     // dt <= dt_safety * smallest collision period
  bool allow_unstable_dt = false;
  double duration = 0;        // s of the main stage
  std::optional<double> end_angle;  // rad, when the duration was given as a rotation angle
  double skin = 0;            // m
  std::uint64_t seed = 1;
  double max_overlap = 0.1;   // stop when an overlap exceeds this fraction of the smaller diameter
  double settle_time = 0;     // s of settling before the main stage, rotation off
  Gravity gravity;
  std::vector<SpeciesSpec> species;
  std::string law;  // the contact law's name (laws.hpp)
  std::shared_ptr<ContactTable> contacts;
  CriticalStep critical;
  std::vector<Wall> walls;
  MeshWalls mesh_walls;  // [[wall]] of type "mesh" (systems/walls/mesh_wall_scene.hpp)
  PeriodicBox periodic;  // [periodic]: axes whose faces wrap
  std::vector<FillSpec> fills;
  FlowSpec flow;  // [[feed]] and [[outlet]] (systems/setup/flow_scene.hpp)
  OutputSpec output;
  int segregation_type = -1;  // the larger species of a binary mixture, else -1
  double segregation_cell = 0;  // m
  // [analysis]: Lacey's index (binary mixtures) over cubic cells of this edge, counting cells of at
  // least this many grains (systems/analysis/mixing.hpp).
  double mixing_cell = 0;  // m
  int mixing_min_grains = 10;
  std::optional<LayerSettings> layers;  // [analysis.layers]: layers.csv of a continuous mixer
  std::shared_ptr<const BodiesSpec> bodies;  // [[shape]] and [[bodies]]; null when the scene has none
  bool pattern = false;  // moon/petal classifier and free-surface angle: a drum and two species

  std::int64_t main_steps() const;
  std::int64_t settle_steps() const;
  // Whether any species rotates: without rotation the grains have no spin columns at all.
  bool spin() const {
    for (const SpeciesSpec& sp : species)
      if (sp.rotates) return true;
    return false;
  }
};

// Reads and validates everything; throws SceneError naming file, line, key and fix.
DemScene load_dem_scene(const SceneDoc& doc);

// How a scene that holds more than grains (a liquid beside them) has its DEM part read.
struct DemLoadOptions {
  // The step is the caller's: run.dt is not read as the DEM step and not checked against the contact
  // law's limit (the caller sets DemScene::dt and checks it); this value stands in for run.dt in the
  // checks of durations and output intervals.
  std::optional<double> outer_dt;
  // Off when the caller reads more of the scene and checks for unknown keys itself.
  bool check_unused_keys = true;
};
DemScene load_dem_scene(const SceneDoc& doc, const DemLoadOptions& options);

// The grains of fill f (in s.fills): a random fill's placed clear of `existing` and of the walls, a
// state file's rows with their types mapped, diameters checked and centres inside the walls. A
// SceneError names the fill and, for a file, its line.
std::vector<PlacedGrain> place_fill(const DemScene& s, const FillSpec& f, std::span<const PlacedGrain> existing);
// A [[fill]]'s region table (box or cylinder; a cylinder's max_height measured against gravity).
Region read_fill_region(const SceneNode& node, const Gravity& g);
// Refuses a wall whose translation m moves it more than 0.1 of `smallest` (m; `what` names it) per
// step, at the motion's key, naming the likely unit mistakes.
void require_motion_step(const DemScene& s, const SceneNode& w, const WallMotion& m, double smallest,
                         const std::string& what);
// The index of the species called `name` (the value of `key` in `node`); a SceneError listing the
// scene's species if there is none.
std::int32_t species_index(const DemScene& s, const SceneNode& node, std::string_view key, const std::string& name);

// The DEM systems of one step in phase order, with the drivers of the scene's contact law.
// The force terms the DEM step's integrator sums: pair contacts, then walls (when the scene has any).
ForceTerms dem_force_terms(const DemScene& scene);
// The DEM step built from the scene: the integrator's two halves, the broadphase, the pair contacts of
// the scene's law, and wall contacts only when the scene has walls.
void schedule_dem_step(Schedule& step, const DemScene& scene);

// Creates the grains of every fill (random placement, state files) and the resources.
// Random fills that cannot be placed, or a state file that does not match the scene, are errors
// naming the scene file and the fill.
void build_dem_world(const DemScene& scene, World& world);

// Estimated bytes for n grains (columns, neighbour list and history at a typical coordination).
std::size_t estimate_memory_bytes(const DemScene& scene, std::size_t n);
// Neighbour-list pairs per grain the estimate counts for n grains (it grows with run.skin).
std::size_t list_pairs_per_grain(const DemScene& scene, std::size_t n);
std::size_t planned_grain_count(const DemScene& scene);
// Refuses (SceneError) n grains whose arrays would need more than 80 % of this machine's memory.
void require_memory(const DemScene& scene, std::size_t n);
// The most grains the table may hold by that rule (a feed stops the run with an error past it).
std::size_t memory_grain_limit(const DemScene& scene);

}  // namespace gf
