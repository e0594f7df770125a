// Composite grains in a DEM scene: the [[shape]] and [[bodies]] tables read and validated, the
// Bodies and Members tables built from them, and the bodies' step. Keys (SI units):
//   [[shape]]   name; kind = "box" (size = [x, y, z]), "triangular_prism" (side, length),
//               "up_down_cone" (base_radius, neck_radius, height, facets = 12, join = "narrow_ends" or
//               "wide_ends"), "letter" (letter = O T Z K A C, width, height, depth, stroke), "file"
//               (path of an .obj or .stl, relative to the scene), "sphere" (a point dilated by
//               radius: a sphere, with exact mass properties and no grid), "spheres" (centres =
//               [[x, y, z], ...]: a clump of spheres of that radius, overlapping or not, the
//               multi-sphere approximation of a shape), "ellipsoid" (semi_axes = [a, b, c], the grain's
//               outer ones: a smooth core, member_core.hpp; exact mass properties and no grid when radius
//               is 0); radius (dilation, m, >= 0; > 0 under
//               hertz_mindlin); density (kg/m^3); grid (voxel edge of the mass properties, m, default a
//               tenth of the shape's smallest bounding-box edge); under hertz_mindlin also
//               youngs_modulus and poisson_ratio, the same for every shape (one material for all bodies).
//   [[bodies]]  shape (a [[shape]] name); file = a body frame CSV that a run wrote (its moving
//               bodies of this shape, with their pose, velocity and spin: a restart from that frame),
//               or positions = [[x, y, z], ...] (centres of mass) or count with
//               region = { shape = "box", lo, hi } or a cylinder as a random fill's (bounding spheres
//               kept apart; optional seed; arrangement = "random" (default) or "lattice": a cubic
//               lattice of bounding spheres filled from the bottom of a box region, for dense starts);
//               orientation = "identity" (default) or "random"; velocity;
//               fixed = true (the bodies never move: walls, floors, gates built of shapes; the law's
//               [contact.wall] parameters act between them and moving bodies); remove_at = t (s of the
//               main stage, after [settle]: the bodies are removed then, their contact springs
//               dropped, e.g. a hopper's gate); group = k (an integer >= 0, default the table's index:
//               the colour of pictures by group, and a column of the frames).
//   [output]    series_interval, frame_interval (s) as for grains; picture_interval (s, 0 = none: a
//               side view of the bodies every interval of simulated time, pictures/time_SSSS.SSSS.png),
//               picture_size (px, the longer side, default 800), picture_colour = "group" (default) or
//               "layer" (five layers of equal counts by height at the start of the main stage,
//               alternately blue and vermillion, as the seed's hopper), picture_view = "z" (default:
//               looking along -z, x to the right) or "x" (looking along +x, z to the right).
//               checkpoint_interval, checkpoint_keep_all, checkpoint_at_end as for grains
//               (dem_body_checkpoint.hpp: a resumed run is bit-identical).
//   [analysis]  outlet_height (m, along -gravity, i.e. y under the default gravity): series.csv adds
//               remaining_fraction, the moving bodies whose centre of mass lies above it over those
//               moving at the start of the main stage. [[analysis.repose]]: heaps, ridges or craters
//               whose angle of repose summary.json reports at the end (systems/setup/repose_scene.hpp).
//   [sink]      height (m, along -gravity): a moving body whose centre falls below it is removed (so
//               grains discharged from a hopper need no floor to pile on).
// run.max_overlap is a fraction of the thinnest moving shape's smallest outer dimension: a member
// contact overlapping more stops the run (exit status 3), as for grains.
// Bodies touch each other member by member and the scene's plane, box, cylinder and drum walls,
// with the [contact] law; a cylinder or drum may turn (omega), its surface's velocity felt at the
// contact, and a plane may turn about its own normal (a drum's end plate); the walls stand still
// while the fill settles. Spheres share a scene with bodies as [[shape]] kind = "sphere": bodies of
// one point member, which meet members as any member does (member_geometry.hpp), stepped with the
// bodies (at a body's cost, not a grain's); [[species]] and [[fill]] place such spheres too
// (body_sphere_fill.hpp). Not yet in one scene with bodies: [[feed]] and [[outlet]], mesh walls,
// planes turning about another axis (they sweep through the bodies) and [periodic]; such scenes are
// refused.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "engine/scene.hpp"
#include "engine/schedule.hpp"
#include "engine/world.hpp"
#include "systems/analysis/body_repose.hpp"
#include "systems/bodies/body_shapes.hpp"
#include "systems/bodies/mass_properties.hpp"
#include "systems/contact/contact_table.hpp"

namespace gf {

struct DemScene;

struct BodyShape {
  std::string name;
  int line = 0;
  ShapeSpec shape;
  MassProperties props;
  double bound = 0;  // m, a sphere about the centre of mass holding the dilated shape
};

struct BodyPlacement {
  std::size_t shape = 0;
  int line = 0;
  bool fixed = false;
  double remove_at = -1;  // s of the main stage; < 0: never
  int group = 0;
  std::array<double, 3> x{};                    // m, centre of mass
  std::array<double, 4> q{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z), the shape frame to the world
  std::array<double, 3> v{};                    // m/s
  std::array<double, 3> w{};                    // rad/s, world frame
};

// The outputs and analyses of a body scene (keys above).
struct BodyOutputSpec {
  double picture_interval = 0;  // s, 0 = none
  int picture_size = 800;       // px, the longer side
  bool colour_by_layer = false;  // else by group (or by shape)
  bool colour_by_shape = false;
  int view_axis = 2;            // the axis looked along: 2 (z, x to the right) or 0 (x, z to the right)
  bool has_outlet = false;
  double outlet_height = 0;     // m along -gravity
  bool has_sink = false;
  double sink_height = 0;       // m along -gravity
  double overlap_scale = 0;     // m, the thinnest moving shape's smallest outer dimension
  std::vector<ReposeSpec> repose;  // [[analysis.repose]]: heaps measured at the end of the run
};

struct BodiesSpec {
  int line = 0;  // the first [[bodies]] table
  std::vector<BodyShape> shapes;
  std::vector<BodyPlacement> placed;
  BodyOutputSpec output;
  CriticalStep critical{0.0, ""};
  // The same terms with each shape's rim mass (rim_mass) for its body mass: the period of a grain
  // rocked by a contact at its rim, shorter than `critical` for any shape but a sphere. A step above
  // dt_safety of it is a warning, not refused: one such contact is still resolved, but a flat grain
  // pressed at several rim points at once (plates stacked face to face) can rock unstably.
  CriticalStep rim{0.0, ""};
  std::function<void(World&)> install_model;  // emplaces BodyContactModel<L> of the scene's law
  std::function<void(Schedule&)> schedule_contacts;  // BodyContact<L>
};

// The smallest mass a contact at the shape's rim meets. A force along n at r from the centre of mass
// moves that point as a free mass 1 / (1/m + (r x n)^T I^-1 (r x n)) would; the smallest over the
// cores' vertices and every n (a cube's corner: m / 5.5; a flat letter's corner: about m / 6). A
// sphere's is its mass.
double rim_mass(const BodyShape& shape);

// Whether the scene has [[bodies]] tables.
bool scene_has_bodies(const SceneNode& root);
// Refuses (SceneError) what bodies cannot share a scene with yet; call before the walls are read.
// [output] and [analysis] of a body scene are read by read_bodies (the grains' readers skip them).
void require_body_scene(const SceneNode& root);
// Reads [[shape]] and [[bodies]] with the scene's [contact] law (s.law, s.seed, s.gravity set).
BodiesSpec read_bodies(const DemScene& s, const SceneNode& root);
// The Bodies and Members tables, the planes and the contact state, and the resources the step reads.
void build_body_world(const DemScene& s, World& world);
// The bodies' step: integrator halves around the members' placement and the contacts.
void schedule_body_step(Schedule& step, const DemScene& s);

}  // namespace gf
