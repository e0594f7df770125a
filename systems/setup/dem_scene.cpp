#include "systems/setup/dem_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "engine/machine_memory.hpp"
#include "systems/analysis/metrics.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/fill/state_csv.hpp"
#include "systems/setup/flow_scene.hpp"
#include "systems/setup/scene_fields.hpp"
#include "systems/setup/species_size.hpp"
#include "systems/walls/wall_fields.hpp"
#include "systems/walls/contact_systems.hpp"
#include "systems/walls/mesh_wall_scene.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

namespace {

Vec3d to_v(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

Vec3d unit_vector(const SceneNode& node, std::string_view key, std::array<double, 3> fallback, bool required) {
  const std::array<double, 3> a = required ? node.get_vec3(key) : node.get_vec3(key, fallback);
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(len > 0.0)) node.fail(key, "a direction must not be the zero vector", "give a non-zero vector, e.g. [0, 0, 1]");
  return {a[0] / len, a[1] / len, a[2] / len};
}

// Species of a size distribution: the table's constants are their smallest grains' (which set the
// critical step), rescaled in the drivers to each contact's grains (size_scaling.hpp), for a law that
// says how its constants scale.
template <class Law>
void size_contacts(DemScene& s, const std::vector<SceneNode>& species_nodes) {
  bool any = false;
  for (std::size_t k = 0; k < s.species.size(); ++k) {
    if (s.species[k].size.is_fixed()) continue;
    any = true;
    if constexpr (!SizedLaw<Law>)
      species_nodes[k].fail("diameter",
                            "the " + std::string(Law::name) + " law's model particles have one size per species",
                            "give the species one diameter (m), or use linear_spring_dashpot or hertz_mindlin");
  }
  if (!any) return;
  std::vector<double> mass, radius;
  for (const SpeciesSpec& sp : s.species) mass.push_back(sp.mass), radius.push_back(0.5 * sp.smallest());
  s.contacts->set_nominal_grains(mass, radius);
}

// [contact] for every pair; [contact.wall] and [[contact.pair]] override single keys. The law
// reads its own keys, and each species' material from its [[species]] table.
template <class Law>
void read_contacts(DemScene& s, const SceneNode& root, const SceneNode& ct) {
  using Params = typename Law::Params;
  const std::size_t n = s.species.size();
  std::vector<ContactBody<typename Law::Material>> bodies;
  std::vector<std::string> names;
  const auto species_nodes = root.tables("species");
  for (std::size_t k = 0; k < n; ++k) {
    const SpeciesSpec& sp = s.species[k];
    bodies.push_back({sp.mass, sp.inertia, 0.5 * sp.smallest(), Law::read_material(species_nodes[k]), false});
    bodies.back().gravity = std::hypot(s.gravity.x, s.gravity.y, s.gravity.z);
    names.push_back(sp.name);
  }
  // A law that needs more of the scene (no rotation, a weight) says so at the scene's keys.
  if constexpr (requires { Law::check_scene(root, 1.0); })
    Law::check_scene(root, std::hypot(s.gravity.x, s.gravity.y, s.gravity.z));
  const Params base = Law::read_params(ct, nullptr, false);
  std::vector<Params> pp(n * n, base);
  const auto wall = ct.maybe_table("wall");
  std::vector<Params> pw(n, wall ? Law::read_params(*wall, &base, true) : base);
  for (const SceneNode& pr : ct.tables("pair")) {
    const std::string a = pr.get_string(kContactPairFields.field("species_a").key);
    const std::string b = pr.get_string(kContactPairFields.field("species_b").key);
    const std::int32_t ia = species_index(s, pr, "species_a", a), ib = species_index(s, pr, "species_b", b);
    const Params p = Law::read_params(pr, &base, false);
    pp[ia * n + ib] = p;
    pp[ib * n + ia] = p;
  }
  s.contacts = std::make_shared<ContactTable>(make_contact_table<Law>(bodies, names, pp, pw));
  size_contacts<Law>(s, species_nodes);
}

// A wall surface moving at `omega` times `radius` may travel at most 0.1 of the smallest diameter per
// step: faster, it passes through grains between two contact evaluations (1e9 rad/s moved the seed
// drum's wall 750 m per step, reported as an overlap instability). A radius of more than 500 of the
// largest grains is named as the likelier mistake: a radius typed in millimetres.
void require_wall_step(const DemScene& s, const SceneNode& w, double omega, double radius) {
  if (s.species.empty()) return;  // composite grains: read_bodies checks against the thinnest shape
  double smallest = s.species.front().smallest(), largest = 0.0;
  for (const SpeciesSpec& sp : s.species) smallest = std::min(smallest, sp.smallest()), largest = std::max(largest, sp.largest());
  const double step = std::abs(omega) * radius * s.dt;
  if (step <= 0.1 * smallest) return;
  const std::string moves = "the wall's surface moves " + short_number(step) + " m per step, more than 0.1 of the "
                            "smallest diameter (" + short_number(smallest) + " m)";
  if (radius > 500 * largest)
    w.fail("radius", moves + ", and its radius " + number_text(radius) + " m is " + short_number(radius / largest) +
                         " diameters of the largest grain",
           "is the radius in millimetres? " + number_text(radius) + " mm is " + number_text(radius * 1e-3) +
               " m; otherwise lower omega (rad/s) or run.dt");
  w.fail("omega", moves, "lower omega (rad/s) or run.dt");
}

// `n` points on a circle about `center` in the plane normal to the unit `axis` (a drum end's outline).
std::vector<Vec3d> circle_points(const Vec3d& center, const Vec3d& axis, double radius, int n) {
  const Vec3d trial = std::abs(axis.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  Vec3d u = trial - dot(trial, axis) * axis;
  u = (1.0 / std::sqrt(dot(u, u))) * u;
  const Vec3d v = cross(axis, u);
  std::vector<Vec3d> out;
  for (int k = 0; k < n; ++k) {
    const double a = 2.0 * std::numbers::pi * k / n;
    out.push_back(center + (radius * std::cos(a)) * u + (radius * std::sin(a)) * v);
  }
  return out;
}

// A wall's translation (wall_motion.hpp), its step checked against the smallest diameter
// (composite grains: against the thinnest shape, in read_body_outputs).
WallMotion read_motion(const DemScene& s, const SceneNode& w, bool bodies) {
  if (!has_wall_motion(w)) return {};
  WallMotion m = read_wall_motion(w);
  if (bodies || s.species.empty()) return m;
  double smallest = s.species.front().smallest();
  for (const SpeciesSpec& sp : s.species) smallest = std::min(smallest, sp.smallest());
  require_motion_step(s, w, m, smallest, "the smallest diameter");
  return m;
}

// The narrowest width of a fill region (m): a grain wider than it cannot be placed.
double narrowest(const Region& r) {
  if (r.kind == Region::Kind::Box)
    return std::min({r.hi[0] - r.lo[0], r.hi[1] - r.lo[1], r.hi[2] - r.lo[2]});
  return std::min({2.0 * r.radius, r.length, r.radius + r.max_height});
}

// A grain wider than the region it is poured into: most often a diameter typed in millimetres. Named at the
// species' diameter, before the fill's placement attempts say "lower the count".
void require_grains_fit(const DemScene& s, const SceneNode& root, const SceneNode& fill, const FillSpec& spec) {
  const double room = narrowest(spec.region);
  for (const auto& [sp, n] : spec.counts) {
    const double d = s.species[sp].largest();
    if (n == 0 || d <= room) continue;
    root.tables("species")[sp].fail(
        "diameter", "species '" + s.species[sp].name + "' has " + (s.species[sp].size.is_fixed() ? "" : "grains of ") +
                        "diameter " + number_text(d) + " m, wider than " +
                        spec.where + "'s region (" + short_number(room) + " m at its narrowest, line " +
                        std::to_string(fill.line()) + ")",
        "is the diameter in millimetres? " + number_text(d) + " mm is " + number_text(d * 1e-3) +
            " m; otherwise enlarge the region");
  }
}

// [periodic] x|y|z = [min, max] (m): faces of the box along that axis are periodic. The box must
// exceed twice a pair's reach (the largest diameter and the skin) plus a skin, so that no pair of
// grains is in reach both directly and through an image.
void read_periodic(DemScene& s, const SceneNode& root) {
  const auto node = root.maybe_table("periodic");
  if (!node) return;
  double dmax = 0.0;
  for (const SpeciesSpec& sp : s.species) dmax = std::max(dmax, sp.largest());
  const std::string_view names[3] = {kPeriodicFields.field("x").key, kPeriodicFields.field("y").key,
                                     kPeriodicFields.field("z").key};
  for (int d = 0; d < 3; ++d) {
    if (!node->has(names[d])) continue;
    const std::vector<double> v = node->get_doubles(names[d]);
    if (v.size() != 2 || !(v[1] > v[0]))
      node->fail(names[d], "give the box along this axis as [min, max] with max > min (m)",
                 "e.g. " + std::string(names[d]) + " = [-0.02, 0.02]");
    const double shortest = 2.0 * (dmax + s.skin) + s.skin;
    if (v[1] - v[0] < shortest)
      node->fail(names[d], "the periodic length " + short_number(v[1] - v[0]) + " m is shorter than " +
                               short_number(shortest) + " m, twice a pair's reach (largest diameter + run.skin) "
                               "plus the skin: a pair of grains would meet twice",
                 "lengthen the box to at least " + short_number(shortest) + " m");
    s.periodic.on[d] = true;
    s.periodic.lo[d] = v[0];
    s.periodic.hi[d] = v[1];
  }
  if (!s.periodic.any())
    root.fail("periodic", "the [periodic] table names no axis", "give x, y or z = [min, max] (m), or remove the table");
}

// A [[wall]] of type "mesh": a triangle mesh, for spherical grains only.
void add_mesh_wall(DemScene& s, const SceneNode& w, const std::string& name, bool bodies) {
  if (s.bodies || s.species.empty())
    w.fail("type", "mesh walls act on spherical grains ([[species]]), not on composite bodies",
           "use plane, box, cylinder or drum walls in a scene of [[bodies]]");
  double largest = 0.0, smallest = s.species.front().smallest();
  for (const SpeciesSpec& sp : s.species)
    largest = std::max(largest, sp.largest()), smallest = std::min(smallest, sp.smallest());
  const double reach = 0.5 * largest + mesh_wall_reach(*s.contacts);
  s.mesh_walls.list.push_back(read_mesh_wall(w, name, reach, smallest, s.dt));
  s.mesh_walls.list.back().motion = read_motion(s, w, bodies);
}

void read_walls(DemScene& s, const SceneNode& root, bool bodies) {
  const FieldTable& t = kWallFields;
  for (const SceneNode& w : root.tables("wall")) {
    const std::string type = read_choice(w, t.field("type"), {"plane", "box", "cylinder", "drum", "mesh"});
    const std::string name = w.get_string(t.field("name").key, type);
    if (type == "mesh") {
      add_mesh_wall(s, w, name, bodies);
      continue;
    }
    if (type == "plane") {
      Wall p;
      p.kind = Wall::Kind::Plane;
      p.name = name;
      p.point = to_v(w.get_vec3(t.field("point").key));
      p.normal = unit_vector(w, t.field("normal").key, {0, 0, 1}, true);
      p.omega = read_number(w, t.field("omega"));
      p.rot_point = to_v(w.get_vec3(t.field("rotation_point").key, {p.point.x, p.point.y, p.point.z}));
      p.rot_axis = unit_vector(w, t.field("rotation_axis").key, {p.normal.x, p.normal.y, p.normal.z}, false);
      p.motion = read_motion(s, w, bodies);
      s.walls.push_back(p);
    } else if (type == "box") {
      const auto lo = w.get_vec3(t.field("lo").key);
      const auto hi = w.get_vec3(t.field("hi").key);
      for (int d = 0; d < 3; ++d)
        if (!(hi[d] > lo[d])) w.fail("hi", "each component of hi must exceed lo's", "swap or correct lo and hi");
      const WallMotion motion = read_motion(s, w, bodies);
      const char* faces[6] = {"-x", "+x", "-y", "+y", "-z", "+z"};
      for (int f = 0; f < 6; ++f) {
        Wall p;
        p.kind = Wall::Kind::Plane;
        p.name = name + faces[f];
        const int d = f / 2;
        const bool upper = f % 2 == 1;
        std::array<double, 3> pt = upper ? hi : lo;
        std::array<double, 3> nm{0, 0, 0};
        nm[d] = upper ? -1.0 : 1.0;
        p.point = to_v(pt);
        p.normal = to_v(nm);
        p.rot_point = p.point;
        p.rot_axis = p.normal;
        p.motion = motion;
        // The face's rectangle: the two other axes at lo and hi.
        const int a = (d + 1) % 3, b = (d + 2) % 3;
        for (const auto& [ua, ub] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{1, 1}, std::pair{0, 1}}) {
          std::array<double, 3> c = pt;
          c[a] = ua ? hi[a] : lo[a];
          c[b] = ub ? hi[b] : lo[b];
          p.outline.push_back(to_v(c));
        }
        s.walls.push_back(p);
      }
    } else {
      Wall c;
      c.kind = Wall::Kind::CylinderInner;
      c.name = name;
      c.center = to_v(w.get_vec3(t.field("center").key));
      c.axis = unit_vector(w, t.field("axis").key, {0, 0, 1}, true);
      // A kilometre-wide drum is a typo (a radius of 1e308 overflowed the series' arrays).
      c.radius = read_number(w, t.field("radius"));
      c.omega = read_number(w, t.field("omega"));
      require_wall_step(s, w, c.omega, c.radius);
      c.rot_point = c.center;
      c.rot_axis = c.axis;
      c.motion = read_motion(s, w, bodies);
      if (type == "drum") {
        const double length = read_number(w, t.field("length"));
        c.length = length;
        s.walls.push_back(c);
        for (int side = 0; side < 2; ++side) {
          Wall e;
          e.kind = Wall::Kind::Plane;
          e.name = name + (side == 0 ? "-end-" : "-end+");
          const double sgn = side == 0 ? -1.0 : 1.0;
          e.point = c.center + (sgn * 0.5 * length) * c.axis;
          e.normal = (-sgn) * c.axis;
          e.omega = c.omega;
          e.rot_point = c.center;
          e.rot_axis = c.axis;
          e.motion = c.motion;
          e.outline = circle_points(e.point, c.axis, c.radius, 96);
          s.walls.push_back(e);
        }
      } else {
        s.walls.push_back(c);
      }
    }
  }
  for (Wall& w : s.walls) {
    w.cur_point = w.point;
    w.cur_normal = w.normal;
    w.cur_center = w.center;
    w.cur_axis = w.axis;
  }
}

Region read_region(const SceneNode& f, const Gravity& g) {
  const SceneNode r = f.table("region");
  const FieldTable& t = kRegionFields;
  const std::string shape = read_choice(r, t.field("shape"), {"box", "cylinder"});
  Region region;
  if (shape == "box") {
    region = Region::box(r.get_vec3(t.field("lo").key), r.get_vec3(t.field("hi").key));
  } else {
    const double glen = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
    const std::array<double, 3> up =
        glen > 0 ? std::array<double, 3>{-g.x / glen, -g.y / glen, -g.z / glen} : std::array<double, 3>{0, 1, 0};
    const Vec3d axis = unit_vector(r, t.field("axis").key, {0, 0, 1}, true);
    region = Region::cylinder(r.get_vec3(t.field("center").key), {axis.x, axis.y, axis.z},
                              read_number(r, t.field("radius")), read_number(r, t.field("length")),
                              read_number(r, t.field("max_height")), up);
  }
  if (const std::string why = region.problem(); !why.empty()) r.fail("shape", why, "correct the region's geometry");
  return region;
}

void read_fills(DemScene& s, const SceneNode& root) {
  const auto fills = root.tables("fill");
  if (fills.empty() && root.tables("feed").empty())
    root.fail("fill", "the scene places no grains",
              "add a [[fill]] table: kind = \"random\" with a region and counts, or kind = \"file\" with a path");
  int index = 0;
  for (const SceneNode& f : fills) {
    FillSpec spec;
    spec.line = f.line();
    spec.where = "fill[" + std::to_string(index) + "]";
    const std::string kind = f.get_choice(kFillFields.field("kind").key, {"random", "file"});
    if (kind == "random") {
      spec.kind = FillSpec::Kind::Random;
      spec.region = read_region(f, s.gravity);
      spec.seed = static_cast<std::uint64_t>(f.get_int("seed", static_cast<std::int64_t>(s.seed) + index, 0,
                                                       std::numeric_limits<std::int64_t>::max()));
      const bool by_count = f.has("count");
      const bool by_fraction = f.has("volume_fraction");
      if (by_count == by_fraction)
        f.fail("count", "give exactly one of 'count' and 'volume_fraction'",
               "e.g. count = { small = 1000 } or volume_fraction = { small = 0.3 }");
      const SceneNode m = f.table(by_count ? "count" : "volume_fraction");
      for (const std::string& name : m.keys()) {
        const std::int32_t sp = species_index(s, m, name, name);
        std::size_t n;
        if (by_count) {
          const Range counts = kFillFields.field("count.<species>").range;
          n = static_cast<std::size_t>(m.get_int(name, static_cast<std::int64_t>(counts.lo), static_cast<std::int64_t>(counts.hi)));
        } else {
          const double frac = m.get_double(name, kFillFields.field("volume_fraction.<species>").range);
          // A distribution's grains at their mean volume, pi/6 E[d^3].
          const SizeDistribution& size = s.species[sp].size;
          n = count_for_volume_fraction(spec.region, frac, 0.5 * (size.is_fixed() ? size.value : std::cbrt(size.moment(3))));
        }
        spec.counts.emplace_back(sp, n);
      }
      require_grains_fit(s, root, f, spec);
    } else {
      spec.kind = FillSpec::Kind::File;
      spec.path = root.doc().resolve(f.get_string("path"));
      const SceneNode m = f.table("types");
      for (const std::string& key : m.keys()) {
        char* end = nullptr;
        const long t = std::strtol(key.c_str(), &end, 10);
        if (end == key.c_str() || *end != '\0')
          m.fail(key, "a key of 'types' must be the integer type used in the file",
                 "write e.g. types = { 1 = \"small\", 2 = \"large\" }");
        spec.type_map.emplace_back(static_cast<std::int32_t>(t), species_index(s, m, key, m.get_string(key)));
      }
      if (spec.type_map.empty()) f.fail("types", "no type mapping given", "map every type in the file to a species");
    }
    s.fills.push_back(std::move(spec));
    ++index;
  }
}

void read_pictures(DemScene& s, const SceneNode& out) {
  OutputSpec& o = s.output;
  const FieldTable& t = kOutputFields;
  if (out.has(t.field("picture_angles").key)) {
    o.picture_angles = out.get_doubles("picture_angles");
    for (double a : o.picture_angles)
      if (a < 0) out.fail("picture_angles", "angle " + short_number(a) + " rad is negative", "give rotation angles >= 0 (rad)");
    std::sort(o.picture_angles.begin(), o.picture_angles.end());
    o.picture_angles.erase(std::unique(o.picture_angles.begin(), o.picture_angles.end()), o.picture_angles.end());
    for (std::size_t k = 1; k < o.picture_angles.size(); ++k)
      if (picture_name(o.picture_angles[k - 1]) == picture_name(o.picture_angles[k]))
        out.fail("picture_angles",
                 "angles " + short_number(o.picture_angles[k - 1]) + " and " + short_number(o.picture_angles[k]) +
                     " rad would share the file " + picture_name(o.picture_angles[k]),
                 "file names carry two decimals: keep requested angles at least 0.01 rad apart");
  }
  o.picture_interval = read_number(out, t.field("picture_interval"));
  if (o.picture_interval > 0 && o.picture_interval < 0.01)
    out.fail("picture_interval", "pictures closer than 0.01 rad would share file names (two decimals)",
             "use an interval of at least 0.01 rad, or 0 for none");
  if (o.picture_interval > 0)
    for (double a : o.picture_angles) {
      const double k = std::round(a / o.picture_interval), m = k * o.picture_interval;
      if (picture_name(m) == picture_name(a) && m != a)
        out.fail("picture_angles",
                 "angle " + short_number(a) + " rad would share the file " + picture_name(a) + " with the interval's " +
                     short_number(m) + " rad",
                 "move the angle onto the interval's grid or at least 0.01 rad away from it");
    }
  const std::string colour = read_choice(out, t.field("picture_colour"), {"species", "speed"});
  o.picture.colour = colour == "speed" ? PictureOptions::Colour::Speed : PictureOptions::Colour::Species;
  o.picture.size = static_cast<int>(read_integer(out, t.field("picture_size")));
  o.picture.speed_max = read_number(out, t.field("picture_speed_max"));
  std::vector<double> diameters;
  for (const SpeciesSpec& sp : s.species) diameters.push_back(sp.mean_diameter());
  o.picture.palette = species_palette(diameters);
  if (o.picture_angles.empty() && o.picture_interval == 0) return;
  const std::string key = out.has("picture_angles") ? "picture_angles" : "picture_interval";
  bool drum = false, rotating = false;
  for (const Wall& w : s.walls) {
    drum = drum || w.kind == Wall::Kind::CylinderInner;
    rotating = rotating || w.omega != 0.0;
  }
  if (!drum)
    out.fail(key, "drum pictures need a drum: the scene has no cylinder or drum wall",
             "add a [[wall]] of type \"drum\" or \"cylinder\", or remove the picture keys");
  const bool later = o.picture_interval > 0 || (!o.picture_angles.empty() && o.picture_angles.back() > 0);
  if (!rotating && later)
    out.fail(key, "no wall rotates, so the rotation angle stays 0 and later pictures would never be drawn",
             "give a wall an omega, or use picture_angles = [0] for one picture of the start");
}

// [analysis.layers]: the transverse layers of a continuous mixer (layer_output.hpp), for the
// species the [analysis] table follows.
void read_layers(DemScene& s, const SceneNode& n) {
  LayerSettings l;
  l.type_a = s.segregation_type;
  const FieldTable& t = kLayersFields;
  const Vec3d axis = unit_vector(n, t.field("axis").key, {1, 0, 0}, true);
  l.axis = {axis.x, axis.y, axis.z};
  const auto inlet = n.get_vec3(t.field("inlet").key);
  l.inlet = {inlet[0], inlet[1], inlet[2]};
  l.distances = n.get_doubles(t.field("distances").key);
  if (l.distances.empty() || l.distances.size() > 10000)
    n.fail("distances", "give between 1 and 10,000 distances from the inlet", "e.g. distances = [0.05, 0.1, 0.15]");
  double largest = 0.0;
  for (const SpeciesSpec& sp : s.species) largest = std::max(largest, sp.largest());
  l.thickness = read_number(n, t.field("thickness"), &largest);
  l.cell = read_number(n, t.field("cell"));
  l.min_grains = static_cast<int>(read_integer(n, t.field("min_grains")));
  l.interval = read_number(n, t.field("interval"));
  l.pool = static_cast<int>(read_integer(n, t.field("pool")));
  if (l.interval < s.dt) n.fail("interval", "shorter than the time step", "use at least run.dt");
  s.layers = l;
}

// [analysis]: the cells of Lacey's index for a binary mixture (after its species are known). The
// default edge is the Danckwerts index's, three large diameters; a cell must at least hold a large
// grain, and a count of 1 would let in single-grain cells, whose fraction is 0 or 1 however mixed
// the bed is.
void read_analysis(DemScene& s, const SceneNode& root) {
  if (s.segregation_type >= 0) s.mixing_cell = s.segregation_cell;
  const auto node = root.maybe_table("analysis");
  if (!node) return;
  if (s.segregation_type < 0)
    root.fail("analysis",
              "the mixing measures compare two species, and the scene has " + std::to_string(s.species.size()),
              "remove the [analysis] table, or define exactly two [[species]]");
  // The species the measures follow (default the larger; on equal diameters the first): a map over
  // size ratios that reach 1 names it, so the radial index keeps its sign across the map.
  const FieldTable& t = kAnalysisFields;
  if (node->has(t.field("species").key)) {
    s.segregation_type = species_index(s, *node, "species", node->get_string("species"));
    s.segregation_cell = 3.0 * s.species[s.segregation_type].mean_diameter();
    s.mixing_cell = s.segregation_cell;
  }
  const double d = s.species[s.segregation_type].mean_diameter();
  s.mixing_cell = read_number(*node, t.field("mixing_cell"), &s.mixing_cell);
  if (s.mixing_cell < d)
    node->fail("mixing_cell",
               "a cell of " + short_number(s.mixing_cell) + " m is narrower than the large grains (" +
                   short_number(d) + " m) and holds one of them at most",
               "give at least " + short_number(d) + " m; the default is three large diameters, " +
                   short_number(3.0 * d) + " m");
  s.mixing_min_grains = static_cast<int>(read_integer(*node, t.field("mixing_min_grains")));
  if (auto layers = node->maybe_table(t.field("layers").key)) read_layers(s, *layers);
}

}  // namespace

Region read_fill_region(const SceneNode& node, const Gravity& g) { return read_region(node, g); }

std::int32_t species_index(const DemScene& s, const SceneNode& node, std::string_view key, const std::string& name) {
  for (std::size_t i = 0; i < s.species.size(); ++i)
    if (s.species[i].name == name) return static_cast<std::int32_t>(i);
  std::string names;
  for (auto& sp : s.species) names += (names.empty() ? "'" : ", '") + sp.name + "'";
  node.fail(key, "no species is named '" + name + "'", "use one of the [[species]] names: " + names);
}

double SpeciesSpec::grain_mass(double r) const { return size.is_fixed() ? mass : sphere_mass(density, 2.0 * r); }
double SpeciesSpec::grain_inv_inertia(double r) const {
  if (!rotates) return 0.0;
  return size.is_fixed() ? 1.0 / inertia : 1.0 / (0.4 * grain_mass(r) * r * r);
}

std::int64_t DemScene::main_steps() const { return static_cast<std::int64_t>(std::llround(duration / dt)); }
std::int64_t DemScene::settle_steps() const { return static_cast<std::int64_t>(std::llround(settle_time / dt)); }

DemScene load_dem_scene(const SceneDoc& doc) { return load_dem_scene(doc, DemLoadOptions{}); }

namespace {

// [run]'s step, seeds and gravity (its duration: read_duration, once the walls are known).
void read_run(DemScene& s, const SceneNode& run, const DemLoadOptions& options) {
  const FieldTable& t = kRunFields;
  s.dt = options.outer_dt ? *options.outer_dt : read_number(run, t.field("dt"));
  s.dt_safety = read_number(run, t.field("dt_safety"));
  s.allow_unstable_dt = read_bool(run, t.field("allow_unstable_dt"));
  s.skin = read_number(run, t.field("skin"));
  const Field& seed = t.field("seed");
  s.seed = static_cast<std::uint64_t>(run.get_int(seed.key, static_cast<std::int64_t>(seed.fallback), 0,
                                                  std::numeric_limits<std::int64_t>::max()));
  s.max_overlap = read_number(run, t.field("max_overlap"));
  const auto g = run.get_vec3(t.field("gravity").key, {0, -9.81, 0});
  require_acceleration(run, "gravity", g);
  s.gravity = {g[0], g[1], g[2]};
}

void read_species(DemScene& s, const SceneNode& root, bool with_bodies) {
  for (const SceneNode& sp : root.tables("species")) {
    const FieldTable& t = kSpeciesFields;
    SpeciesSpec spec;
    spec.name = sp.get_string(t.field("name").key);
    for (auto& other : s.species)
      if (other.name == spec.name) sp.fail("name", "species '" + spec.name + "' is defined twice", "rename one");
    // Bounds far past any granular material (osmium is 22,600 kg/m^3; a coarse-grained parcel a few cm)
    // that keep the masses, inertias and time-step terms finite: 1e308 kg/m^3 made them infinite.
    spec.size = read_species_size(sp);
    spec.density = read_number(sp, t.field("density"));
    const double r = 0.5 * spec.smallest();
    spec.mass = sphere_mass(spec.density, spec.smallest());
    spec.inertia = 0.4 * spec.mass * r * r;
    spec.rotates = read_bool(sp, t.field("rotates"));
    s.species.push_back(spec);
  }
  if (s.species.empty() && !with_bodies)
    root.fail("species", "the scene defines no species",
              "add [[species]] with name, diameter (m) and density (kg/m^3)");
  if (s.species.size() > static_cast<std::size_t>(kMaxSpecies))
    root.fail("species", "more than " + std::to_string(kMaxSpecies) + " species", "merge species");
}

// run.duration, or run.end_angle over the first rotating wall's speed; then both stages' step counts.
void read_duration(DemScene& s, const SceneNode& root, const SceneNode& run) {
  const FieldTable& t = kRunFields;
  const bool has_duration = run.has(t.field("duration").key), has_angle = run.has(t.field("end_angle").key);
  if (has_duration == has_angle)
    run.fail("duration", "give exactly one of 'duration' (s) and 'end_angle' (rad of drum rotation)",
             "e.g. duration = 2.0 or end_angle = 30.0");
  if (has_duration) {
    s.duration = read_number(run, t.field("duration"));
  } else {
    s.end_angle = read_number(run, t.field("end_angle"));
    double omega = 0.0;
    for (const Wall& w : s.walls)
      if (w.omega != 0.0) {
        omega = std::abs(w.omega);
        break;
      }
    for (const MeshWall& w : s.mesh_walls.list)
      if (omega == 0.0) omega = std::abs(w.omega);
    if (omega == 0.0)
      run.fail("end_angle", "no wall rotates, so a rotation angle does not define a duration",
               "give duration (s) instead, or a wall with omega != 0");
    s.duration = *s.end_angle / omega;
  }
  check_step_count(run, has_duration ? "duration" : "end_angle", s.duration, s.dt);
  if (auto settle = root.maybe_table("settle")) check_step_count(*settle, "time", s.settle_time, s.dt);
}

// [output]'s times and frame fields, a grain scene's pictures, and what a binary mixture reports.
void read_outputs(DemScene& s, const SceneNode& root, bool with_bodies) {
  if (auto out = root.maybe_table("output")) {
    read_output_times(*out, s.dt, s.output);
    const FieldTable& t = kOutputFields;
    s.output.fields.velocity = read_bool(*out, t.field("frame_velocity"));
    s.output.fields.angular_velocity = read_bool(*out, t.field("frame_angular_velocity"));
    s.output.fields.force = read_bool(*out, t.field("frame_force"));
    if (!with_bodies) read_pictures(s, *out);  // a body scene's pictures: read_bodies
  }
  // A binary mixture reports the segregation of its larger species (grains' tables only).
  if (s.species.size() == 2 && !with_bodies) {
    s.segregation_type = s.species[0].mean_diameter() >= s.species[1].mean_diameter() ? 0 : 1;
    s.segregation_cell = 3.0 * s.species[s.segregation_type].mean_diameter();
    for (const Wall& w : s.walls) s.pattern = s.pattern || w.kind == Wall::Kind::CylinderInner;
  }
}

}  // namespace

DemScene load_dem_scene(const SceneDoc& doc, const DemLoadOptions& options) {
  DemScene s;
  s.file = doc.file();
  const SceneNode root = doc.root();
  const SceneNode run = root.table("run");
  read_run(s, run, options);
  const bool with_bodies = scene_has_bodies(root);
  if (with_bodies) require_body_scene(root);
  read_species(s, root, with_bodies);

  const SceneNode ct = root.table("contact");
  s.law = ct.get_choice(kContactFields.field("model").key, law_names());
  with_law(s.law, [&]<class Law>() { read_contacts<Law>(s, root, ct); });
  s.critical = s.contacts->critical_period();
  // Bodies need the walls and fills read first: spheres of the fills join them as bodies.
  if (with_bodies) {
    read_walls(s, root, true);
    read_periodic(s, root);
    if (!root.tables("fill").empty()) read_fills(s, root);
    s.bodies = std::make_shared<const BodiesSpec>(read_bodies(s, root));
    s.critical = s.bodies->critical;
  }

  const double limit = s.dt_safety * s.critical.period;
  if (!options.outer_dt && s.dt > limit && !s.allow_unstable_dt)
    run.fail("dt",
             "time step " + short_number(s.dt) + " s exceeds " + short_number(s.dt_safety) + " of the contact law's smallest time-step term " +
                 short_number(s.critical.period) + " s (" + s.critical.term + "): the limit is " + short_number(limit) + " s",
             "set dt <= " + short_number(limit) + ", or stiffen less, or set allow_unstable_dt = true to run anyway");

  if (!with_bodies) {
    read_walls(s, root, false);
    read_periodic(s, root);
  }
  if (auto settle = root.maybe_table("settle")) s.settle_time = read_number(*settle, kSettleFields.field("time"));
  if (!with_bodies) {
    read_fills(s, root);
    read_flow(s, root);
  }
  read_duration(s, root, run);
  read_outputs(s, root, with_bodies);
  if (!with_bodies) read_analysis(s, root);  // a body scene's [analysis]: read_bodies
  if (options.check_unused_keys) doc.check_all_used();
  return s;
}

ForceTerms dem_force_terms(const DemScene& scene) {
  ForceTerms terms{{pair_force_term()}};
  if (!scene.walls.empty()) terms.list.push_back(wall_force_term());
  if (!scene.mesh_walls.list.empty()) terms.list.push_back(mesh_wall_force_term());
  return terms;
}

void schedule_dem_step(Schedule& step, const DemScene& scene) {
  if (scene.bodies) {
    schedule_body_step(step, scene);
    return;
  }
  const std::string& law = scene.law;
  if (!scene.flow.feeds.empty()) step.emplace<FeedSystem>(scene.flow.feeds, memory_grain_limit(scene));
  // The closing kick may be left to the next opening pass unless rows come or go between the two.
  const bool rows_change = !scene.flow.feeds.empty() || !scene.flow.outlets.empty();
  const auto deferred = rows_change ? nullptr : std::make_shared<DeferredKick>();
  step.emplace<IntegratePositions>(dem_force_terms(scene), deferred);
  step.emplace<Broadphase>();
  if (scene.periodic.any()) step.emplace<PeriodicRefresh>();
  add_contact_systems(step, {law, !scene.walls.empty(), !scene.mesh_walls.list.empty()});
  if (scene.periodic.any()) step.emplace<PeriodicFold>();
  step.emplace<IntegrateVelocities>(dem_force_terms(scene), deferred);
  if (!scene.flow.outlets.empty()) step.emplace<OutletSystem>(scene.flow.outlets);
}

std::size_t planned_grain_count(const DemScene& scene) {
  std::size_t n = 0;
  for (const FillSpec& f : scene.fills) {
    if (f.kind == FillSpec::Kind::Random)
      for (auto& [sp, c] : f.counts) n += c;
  }
  return n;
}

void require_memory(const DemScene& scene, std::size_t n) {
  const double need = static_cast<double>(estimate_memory_bytes(scene, n));
  const double have = static_cast<double>(machine_memory());
  if (!(have > 0) || need <= 0.8 * have) return;
  // Named at the fill asking for the most grains.
  const FillSpec* big = nullptr;
  std::size_t most = 0;
  for (const FillSpec& f : scene.fills) {
    std::size_t c = 0;
    for (auto& [sp, k] : f.counts) c += k;
    if (c >= most) most = c, big = &f;
  }
  throw SceneError(scene.file.string() + ":" + std::to_string(big ? big->line : 0) + ": " +
                   (big ? big->where + ": " : std::string()) + "the fills ask for " + std::to_string(n) +
                   " grains, about " + short_number(need / 1073741824.0) + " GiB of arrays (up to " +
                   std::to_string(list_pairs_per_grain(scene, n)) + " neighbour pairs per grain with run.skin = " +
                   short_number(scene.skin) + " m), more than 80 % of this machine's " +
                   short_number(have / 1073741824.0) + " GiB. Fix: lower the fills' counts or volume fractions, or "
                   "run.skin (0.1 to 0.3 of the smallest diameter)");
}

std::size_t memory_grain_limit(const DemScene& scene) {
  const double have = static_cast<double>(machine_memory());
  if (!(have > 0)) return std::numeric_limits<std::size_t>::max();
  const double per_grain = static_cast<double>(estimate_memory_bytes(scene, 1000000)) / 1e6;
  return static_cast<std::size_t>(0.8 * have / per_grain);
}

// Neighbour-list pairs per grain: 3.4 in a dense pack of the seed drum with its skin (0.15 of the
// small diameter); for a larger skin, the grains of the smallest size within reach d + skin of one
// (+ the law's reach beyond touching, for a law acting apart), at the random-close-packing fraction,
// counted once per pair, and never more than the other grains.
std::size_t list_pairs_per_grain(const DemScene& scene, std::size_t n) {
  if (scene.species.empty()) return 0;  // a scene of composite grains only
  double d_min = scene.species.front().smallest();
  for (const SpeciesSpec& sp : scene.species) d_min = std::min(d_min, sp.smallest());
  const double law_reach = scene.contacts ? scene.contacts->reach() : 0.0;
  const double reach = (d_min + scene.skin + law_reach) / d_min;
  const double most = std::min(0.64 * 8.0 * reach * reach * reach / 2.0, n > 0 ? static_cast<double>(n - 1) : 0.0);
  return static_cast<std::size_t>(std::ceil(std::max(3.4, most)));
}

std::size_t estimate_memory_bytes(const DemScene& scene, std::size_t n) {
  // Arrays the simulation holds, per grain: 25 double columns (16 without rotation), type and id, the skin reference
  // positions, a 64-byte spring record and a flag per wall. A dense pack of the seed drum has about
  // 3.4 list pairs and 1.7 contacts per grain; a list pair keeps rows, 32-bit lanes, type pair, key,
  // flag, two slot maps, the carried index and search scratch (50 bytes), a contact its indices
  // and force (48 bytes) and two generations of the law's history doubles.
  const std::size_t per_grain = (scene.spin() ? 25 : 16) * 8 + 4 + 8 + 3 * 8 + 65 * scene.walls.size() +
                                (scene.mesh_walls.list.empty() ? 0 : sizeof(MeshSlots) + 6 * 8);
  std::size_t width = 0;
  with_law(scene.law, [&]<class Law>() { width = Law::kHistory; });
  const std::size_t per_pair = 50, per_contact = 48 + 2 * 8 * width;
  return n * (per_grain + per_pair * list_pairs_per_grain(scene, n) + per_contact * 17 / 10);
}

namespace {

[[noreturn]] void fill_error(const DemScene& s, const FillSpec& f, const std::string& what) {
  throw SceneError(s.file.string() + ":" + std::to_string(f.line) + ": " + f.where + ": " + what);
}

// Two grains at one place (the same state file given twice, say) would push apart with forces past any
// limit in the first step: refused, naming both. Sorted by position, coincident grains are neighbours.
// `first[k]` is the index of fill k's first grain in `placed`; the message is placed at the fill of the
// later grain.
std::size_t fill_of(const std::vector<std::size_t>& first, std::size_t grain) {
  return static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), grain) - first.begin() - 1);
}

// "at line 12 of state.csv" for a state file's grain, "placed 7th by fill[1]" for a random one.
std::string where_placed(const DemScene& s, const std::vector<PlacedGrain>& placed, const std::vector<std::size_t>& first,
                         std::size_t grain) {
  const std::size_t fill = fill_of(first, grain);
  const FillSpec& f = s.fills[fill];
  if (placed[grain].line > 0) return "at line " + std::to_string(placed[grain].line) + " of " + shown_path(f.path.string());
  return "number " + std::to_string(grain - first[fill]) + " (from 0) of " + f.where;
}

void require_apart(const DemScene& s, const std::vector<PlacedGrain>& placed, const std::vector<std::size_t>& first) {
  std::vector<std::size_t> order(placed.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return placed[a].x < placed[b].x; });
  for (std::size_t k = 1; k < order.size(); ++k) {
    const PlacedGrain& a = placed[order[k - 1]];
    const PlacedGrain& b = placed[order[k]];
    const double r = std::min(a.radius, b.radius);
    if (std::abs(a.x[0] - b.x[0]) < 1e-6 * r && std::abs(a.x[1] - b.x[1]) < 1e-6 * r &&
        std::abs(a.x[2] - b.x[2]) < 1e-6 * r) {
      const std::size_t earlier = std::min(order[k - 1], order[k]), later = std::max(order[k - 1], order[k]);
      fill_error(s, s.fills[fill_of(first, later)],
                 "the grain " + where_placed(s, placed, first, earlier) + " and the grain " +
                     where_placed(s, placed, first, later) + " sit at (" + short_number(a.x[0]) + ", " +
                     short_number(a.x[1]) + ", " + short_number(a.x[2]) +
                     ") m, one on the other. Fix: a state file listed twice, or two fills that repeat grains: "
                     "give each grain once");
    }
  }
}

// The grains' ids, in placement order: a state file's ids are kept (one id in two files is refused, naming both
// lines), and the run numbers the other grains on from past the largest.
std::vector<std::int64_t> grain_ids(const DemScene& s, const std::vector<PlacedGrain>& placed,
                                    const std::vector<std::size_t>& first) {
  std::vector<std::pair<std::int64_t, std::size_t>> given;
  for (std::size_t i = 0; i < placed.size(); ++i)
    if (placed[i].id >= 0) given.emplace_back(placed[i].id, i);
  std::sort(given.begin(), given.end());
  for (std::size_t k = 1; k < given.size(); ++k)
    if (given[k].first == given[k - 1].first)
      fill_error(s, s.fills[fill_of(first, given[k].second)],
                 "id " + std::to_string(given[k].first) + " is given to the grain " +
                     where_placed(s, placed, first, given[k - 1].second) + " and to the grain " +
                     where_placed(s, placed, first, given[k].second) +
                     ". Fix: give the grains of different state files different ids");
  constexpr std::int64_t kLargestId = std::int64_t{1} << 62;  // room for the ids the run hands out after
  if (!given.empty() && given.back().first > kLargestId)
    fill_error(s, s.fills[fill_of(first, given.back().second)],
               "id " + std::to_string(given.back().first) + " of the grain " +
                   where_placed(s, placed, first, given.back().second) + " is above 2^62. Fix: renumber the file's ids");
  std::int64_t next = given.empty() ? 0 : given.back().first + 1;
  std::vector<std::int64_t> ids(placed.size());
  for (std::size_t i = 0; i < placed.size(); ++i) ids[i] = placed[i].id >= 0 ? placed[i].id : next++;
  return ids;
}

}  // namespace

namespace {

// A random fill's grains, clear of `existing` and of every wall (a region reaching through a wall is a
// scene error).
std::vector<PlacedGrain> random_fill_grains(const DemScene& s, const FillSpec& f, std::span<const PlacedGrain> existing) {
  std::vector<FillSpecies> req;
  for (std::size_t k = 0; k < f.counts.size(); ++k) {
    const auto [sp, c] = f.counts[k];
    const SizeDistribution& size = s.species[sp].size;
    req.push_back({sp, 0.5 * size.largest(), c});
    if (size.is_fixed()) continue;
    // Each grain's diameter, from a generator of the fill's own seed and the species' place in it.
    std::mt19937_64 rng(f.seed ^ (0x9e3779b97f4a7c15ull * (k + 1)));
    for (std::size_t q = 0; q < c; ++q) req.back().radii.push_back(0.5 * size.draw(rng));
  }
  std::vector<PlacedGrain> added;
  try {
    added = place_random(f.region, req, f.seed, existing);
  } catch (const FillError& e) {
    fill_error(s, f, e.what());
  }
  // Grains must start clear of every wall; a region reaching through a wall is a scene error.
  for (const PlacedGrain& p : added) {
    for (const Wall& w : s.walls) {
      Vec3d n;
      if (wall_gap(w, to_v(p.x), n) < p.radius)
        fill_error(s, f,
                   "the region reaches through wall '" + w.name + "' (a grain at (" + short_number(p.x[0]) + ", " +
                       short_number(p.x[1]) + ", " + short_number(p.x[2]) + ") m overlaps it). Fix: shrink the region to lie "
                       "inside the walls by at least the largest radius");
    }
    if (const MeshWall* m = overlapped_mesh_wall(s.mesh_walls, to_v(p.x), p.radius))
      fill_error(s, f,
                 "the region reaches through mesh wall '" + m->name + "' (a grain at (" + short_number(p.x[0]) + ", " +
                     short_number(p.x[1]) + ", " + short_number(p.x[2]) + ") m overlaps it). Fix: shrink the region "
                     "to clear the mesh by at least the largest radius");
  }
  return added;
}

// A state file's grains: types mapped to species, diameters the species', centres inside the walls.
std::vector<PlacedGrain> file_fill_grains(const DemScene& s, const FillSpec& f) {
  std::vector<StateRow> rows;
  try {
    rows = read_state_csv(f.path);
  } catch (const StateCsvError& e) {
    fill_error(s, f, e.what());
  }
  if (rows.empty())
    fill_error(s, f, shown_path(f.path.string()) + ": the state file holds no grains. Fix: give a file with rows, or remove the fill");
  std::vector<PlacedGrain> out;
  for (const StateRow& r : rows) {
    std::int32_t sp = -1;
    for (auto& [t, idx] : f.type_map)
      if (t == r.type) sp = idx;
    if (sp < 0)
      fill_error(s, f,
                 shown_path(f.path.string()) + ":" + std::to_string(r.line) + ": type " + std::to_string(r.type) +
                     " is not mapped to a species. Fix: add it to the fill's 'types' table");
    const SpeciesSpec& species = s.species[sp];
    const double lo = species.smallest(), hi = species.largest();
    if (r.diameter < lo - 1e-9 * lo || r.diameter > hi + 1e-9 * hi)
      fill_error(s, f,
                 shown_path(f.path.string()) + ":" + std::to_string(r.line) + ": diameter " + short_number(r.diameter) +
                     " m does not match species '" + species.name + "' (" +
                     (species.size.is_fixed() ? short_number(lo) : short_number(lo) + " to " + short_number(hi)) +
                     " m). Fix: map the type to a species of that diameter");
    // A centre outside a wall is a grain outside the domain (a settled grain may touch a wall,
    // but not sit behind it): the run would start with an overlap past any limit.
    for (const Wall& w : s.walls) {
      Vec3d n;
      if (wall_gap(w, to_v(r.x), n) <= 0.0)
        fill_error(s, f,
                   shown_path(f.path.string()) + ":" + std::to_string(r.line) + ": the grain's centre (" + short_number(r.x[0]) +
                       ", " + short_number(r.x[1]) + ", " + short_number(r.x[2]) + ") m is outside wall '" +
                       w.name + "'. Fix: move the grain inside the walls, or correct the walls");
    }
    out.push_back({r.x, sp, 0.5 * r.diameter, r.v, r.w, r.id, r.line});
  }
  return out;
}

}  // namespace

std::vector<PlacedGrain> place_fill(const DemScene& s, const FillSpec& f, std::span<const PlacedGrain> existing) {
  return f.kind == FillSpec::Kind::Random ? random_fill_grains(s, f, existing) : file_fill_grains(s, f);
}

namespace {

// A scene of composite grains only: no grain rows, and the resources the step and its priming read.
void build_bodies_only(const DemScene& s, World& world) {
  world.grains.spin = false;
  world.grains.resize(0);
  world.grains.extras.attach<WallHistory>(0).shape(s.walls.size(), 0);
  world.clock = Clock{0.0, s.dt, 0};
  world.resources.emplace<Gravity>(s.gravity);
  world.resources.emplace<Walls>().list = s.walls;
  with_law(s.law, [&]<class Law>() { set_layout(world.resources.emplace<PairHistory>(), Law::history()); });
  build_body_world(s, world);
}

}  // namespace

void build_dem_world(const DemScene& s, World& world) {
  if (s.bodies) {
    build_bodies_only(s, world);
    return;
  }
  require_memory(s, planned_grain_count(s));
  Grains& g = world.grains;
  std::vector<PlacedGrain> placed;
  std::vector<std::size_t> first;
  for (const FillSpec& f : s.fills) {
    first.push_back(placed.size());
    const std::vector<PlacedGrain> added = place_fill(s, f, placed);
    placed.insert(placed.end(), added.begin(), added.end());
  }

  require_apart(s, placed, first);
  const std::vector<std::int64_t> ids = grain_ids(s, placed, first);
  // Again with the state files' rows counted, before the grain arrays and the neighbour list exist.
  require_memory(s, placed.size());
  const std::size_t n = placed.size();
  if (n == 0 && s.flow.feeds.empty())
    throw SceneError(s.file.string() + ":" + std::to_string(s.fills.empty() ? 0 : s.fills.front().line) +
                     ": the scene's fills place no grains. Fix: give a [[fill]] a count or a volume fraction above 0, "
                     "or a state file with rows");
  // Spin columns only when some species rotates; a species that does not has inv_inertia 0.
  g.spin = s.spin();
  g.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const PlacedGrain& p = placed[i];
    const SpeciesSpec& sp = s.species[p.type];
    g.pos.x[i] = p.x[0];
    g.pos.y[i] = p.x[1];
    g.pos.z[i] = p.x[2];
    g.radius.r[i] = p.radius;
    const double m = sp.grain_mass(p.radius);
    g.mass.m[i] = m;
    g.mass.inv_m[i] = 1.0 / m;
    g.mass.inv_inertia[i] = sp.grain_inv_inertia(p.radius);
    g.species.type[i] = p.type;
    g.pid.id[i] = ids[i];
    g.vel.x[i] = p.v[0];
    g.vel.y[i] = p.v[1];
    g.vel.z[i] = p.v[2];
    if (g.spin && sp.rotates) {  // a species that does not rotate keeps zero spin
      g.omega.x[i] = p.w[0];
      g.omega.y[i] = p.w[1];
      g.omega.z[i] = p.w[2];
    }
  }
  g.next_id = n == 0 ? 0 : *std::max_element(ids.begin(), ids.end()) + 1;
  g.extras.attach<WallHistory>(n).shape(s.walls.size(), n);

  world.clock = Clock{0.0, s.dt, 0};
  world.resources.emplace<Gravity>(s.gravity);
  world.resources.emplace<ContactTable>(*s.contacts);
  world.resources.emplace<OverlapLimit>(OverlapLimit{s.max_overlap});
  Walls& walls = world.resources.emplace<Walls>();
  walls.list = s.walls;
  BroadphaseState& bp = world.resources.emplace<BroadphaseState>();
  bp.skin = s.skin;
  bp.reach = s.contacts->reach();
  world.resources.emplace<PeriodicImages>().box = s.periodic;
  world.resources.emplace<NeighborList>();
  with_law(s.law, [&]<class Law>() { set_layout(world.resources.emplace<PairHistory>(), Law::history()); });
  world.resources.emplace<PairForces>();
  if (!s.mesh_walls.list.empty()) attach_mesh_walls(world, s.mesh_walls);
  if (s.flow.any()) {
    try {
      world.resources.emplace<FlowState>(start_flow(s.flow));
    } catch (const std::invalid_argument& e) {
      throw SceneError(s.file.string() + ": " + e.what());
    }
  }
}

void require_motion_step(const DemScene& s, const SceneNode& w, const WallMotion& m, double smallest,
                         const std::string& what) {
  const double step = m.fastest() * s.dt;
  if (!(step > 0.1 * smallest)) return;
  const char* key = w.has("velocity_file") ? "velocity_file" : (w.has("velocity") ? "velocity" : "vibration_amplitude");
  w.fail(key, "the wall's translation reaches " + short_number(m.fastest()) + " m/s and moves it " +
                  short_number(step) + " m per step, more than 0.1 of " + what + " (" + short_number(smallest) + " m)",
         "lower the speed (is it in mm/s? is the amplitude in mm?), the frequency (Hz, not rad/s) or run.dt");
}

}  // namespace gf
