#include "systems/setup/coupled_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "systems/coupling/coupling_fields.hpp"
#include "systems/mps/liquid_fields.hpp"
#include "systems/setup/dem_body_scene.hpp"

namespace gf {

namespace {

// What the coupled step does not carry yet, refused before either part is read.
void refuse_unsupported(const SceneNode& root) {
  const char* fix = "remove the table: liquid and grains run together without it so far";
  if (scene_has_bodies(root)) root.fail("bodies", "composite grains are not coupled to a liquid yet", fix);
  for (const char* key : {"feed", "outlet"})
    if (root.has(key)) root.fail(key, "feeds and outlets are not coupled to a liquid yet", fix);
  if (root.has("settle")) root.fail("settle", "a coupled scene has no dry settling stage", fix);
  const SceneNode liquid = root.table("liquid");
  if (read_integer(liquid, kLiquidFields.field("dim")) != 3)
    liquid.fail("dim", "grains are spheres, so the liquid they sit in is 3D", "set dim = 3");
  const SceneNode run = root.table("run");
  if (!run.has(kLiquidRunFields.field("gravity").key))
    run.fail("gravity", "a coupled scene states its gravity: the liquid's default is none, the grains' -9.81 m/s^2 along y",
             "set gravity = [gx, gy, gz] (m/s^2) in [run]");
}

// Grains may wrap only where the liquid does: along its periodic axis, over the same length.
void check_periodic(const CoupledScene& s, const SceneNode& root) {
  const PeriodicBox& box = s.dem.periodic;
  if (!box.any()) return;
  const Periodicity& per = s.liquid.params.periodic;
  const char* names[3] = {"x", "y", "z"};
  const SceneNode node = root.table("periodic");
  for (int d = 0; d < 3; ++d) {
    if (!box.on[d]) continue;
    if (d != per.axis)
      node.fail(names[d], "the grains wrap along " + std::string(names[d]) + " and the liquid does not",
                per.axis < 0 ? std::string("use a liquid geometry with a periodic axis (channel or pipe), or remove [periodic]")
                             : "make the grains periodic along " + std::string(names[per.axis]) + " only");
    const double tol = 1e-9 * per.period();
    if (std::abs(box.lo[d] - per.lo) > tol || std::abs(box.hi[d] - per.hi) > tol)
      node.fail(names[d], "the grains' period [" + short_number(box.lo[d]) + ", " + short_number(box.hi[d]) +
                              "] m differs from the liquid's [" + short_number(per.lo) + ", " + short_number(per.hi) + "] m",
                "set " + std::string(names[d]) + " = [" + short_number(per.lo) + ", " + short_number(per.hi) + "]");
  }
}

void read_substeps(CoupledScene& s, const SceneNode& c) {
  CouplingSpec& k = s.coupling;
  const double dt = s.liquid.dt;
  k.dem_step_limit = s.dem.dt_safety * s.dem.critical.period;
  const Field& f = kCouplingFields.field("substeps");
  if (k.fixed_grains) {  // nothing moves: the contact law's period sets no limit; at least one step
    k.substeps = static_cast<int>(c.get_int(f.key, 1, 1, static_cast<std::int64_t>(f.range.hi)));
    return;
  }
  const double needed = std::ceil(dt / k.dem_step_limit * (1.0 - 1e-12));
  const std::int64_t given = read_integer(c, f);  // 0, the default: computed
  if (given == 0) {
    if (!(needed <= 1e6))
      c.fail("substeps", "the DEM step limit " + short_number(k.dem_step_limit) + " s needs more than 1e6 sub-steps of run.dt = " + short_number(dt) + " s",
             "soften the contact law, or shorten run.dt");
    k.substeps = static_cast<int>(std::max(1.0, needed));
    k.substeps_computed = true;
    return;
  }
  k.substeps = static_cast<int>(given);
  if (dt / k.substeps > k.dem_step_limit && !s.dem.allow_unstable_dt)
    c.fail("substeps",
           std::to_string(k.substeps) + " sub-steps of run.dt = " + short_number(dt) + " s give a DEM step " +
               short_number(dt / k.substeps) + " s above " + short_number(s.dem.dt_safety) + " of the contact law's smallest period " +
               short_number(s.dem.critical.period) + " s (" + s.dem.critical.term + ")",
           "set substeps >= " + std::to_string(static_cast<long long>(needed)) +
               ", or remove the key to have it computed, or set run.allow_unstable_dt = true");
}

// In a closed box filled with one liquid, gravity is balanced by a hydrostatic pressure and drops out of
// the motion: the liquid may solve for p + rho_l |g| height instead, with no gravity in its step (no
// start-up compression, no sloshing). The grains keep gravity and Archimedes' buoyancy.
void read_modified_pressure(CoupledScene& s, const SceneNode& c) {
  s.coupling.modified_pressure = read_bool(c, kCouplingFields.field("modified_pressure"));
  if (!s.coupling.modified_pressure) return;
  const LiquidGeometry& g = s.liquid.geometry;
  const bool filled = s.liquid.blocks.size() == 1 && s.liquid.blocks[0].lo == g.lo && s.liquid.blocks[0].hi == g.hi;
  if (g.kind != LiquidGeometry::Kind::Box || !filled)
    c.fail("modified_pressure", "only a closed box filled with liquid balances gravity by a hydrostatic pressure",
           "use geometry type = \"box\" with one [[fluid]] block of the geometry's lo and hi, or remove the key");
  s.liquid.params.gravity = {0.0, 0.0, 0.0};
}

void read_coupling(CoupledScene& s, const SceneNode& root) {
  const FieldTable& T = kCouplingFields;
  const SceneNode c = root.table("coupling");
  const double l0 = s.liquid.params.k.l0;
  s.coupling.fixed_grains = read_bool(c, T.field("fixed_grains"));
  read_substeps(s, c);
  s.dem.dt = s.liquid.dt / s.coupling.substeps;
  s.coupling.smoothing_radius = read_number(c, T.field("smoothing_radius"));
  if (s.coupling.smoothing_radius < l0)
    c.fail("smoothing_radius",
           short_number(s.coupling.smoothing_radius) + " m is shorter than the node spacing l0 = " + short_number(l0) +
               " m: a grain between nodes would reach none",
           "set smoothing_radius >= l0, e.g. " + short_number(2.5 * l0) + " m (2.5 l0)");
  s.coupling.drag = &drag_law(read_choice(c, T.field("drag"), drag_law_names()));
  s.coupling.rotational_drag = read_choice(c, T.field("rotational_drag"), {"none", "dennis"}) == "dennis";
  s.coupling.shear_lift = read_choice(c, T.field("shear_lift"), {"none", "saffman_mei"}) == "saffman_mei";
  s.coupling.spin_lift = read_choice(c, T.field("spin_lift"), {"none", "oesterle_bui_dinh"}) == "oesterle_bui_dinh";
  s.coupling.min_liquid_fraction = read_number(c, T.field("min_liquid_fraction"));
  s.coupling.fluid_nodes_only = read_choice(c, T.field("share_with"), {"all_nodes", "fluid_nodes"}) == "fluid_nodes";
  s.coupling.averaged = read_bool(c, T.field("averaged"));
  read_modified_pressure(s, c);
}

}  // namespace

bool is_coupled_scene(const SceneDoc& doc) {
  const SceneNode root = doc.root();
  return root.has("liquid") && (root.has("species") || root.has("fill") || root.has("coupling"));
}

CoupledScene load_coupled_scene(const SceneDoc& doc) {
  const SceneNode root = doc.root();
  refuse_unsupported(root);
  CoupledScene s;
  s.file = doc.file();
  s.liquid = load_liquid_scene(doc, false);
  s.dem = load_dem_scene(doc, DemLoadOptions{s.liquid.dt, false});
  read_coupling(s, root);
  check_periodic(s, root);
  doc.check_all_used();
  return s;
}

const char* drag_model_name(DragModel m) { return m->name.data(); }

}  // namespace gf
