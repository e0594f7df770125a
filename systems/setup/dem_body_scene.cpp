#include "systems/setup/dem_body_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <cstdlib>
#include <random>
#include <sstream>
#include <type_traits>

#include <Eigen/Eigenvalues>

#include "engine/read_file.hpp"
#include "systems/analysis/metrics.hpp"
#include "systems/setup/body_fields.hpp"
#include "systems/setup/body_sphere_fill.hpp"
#include "systems/setup/repose_scene.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/bodies/body_integrate.hpp"
#include "systems/bodies/shape_files.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/laws.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/setup/dem_scene.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

namespace {

Eigen::Vector3d to_e(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

const Field& shape_field(std::string_view key) { return kShapeFields.field(key); }

ShapeSpec build_up_down_cone(const SceneNode& t, double r) {
  UpDownCone c;
  c.base_radius = read_number(t, shape_field("base_radius"));
  c.neck_radius = read_number(t, shape_field("neck_radius"));
  c.height = read_number(t, shape_field("height"));
  c.facets = static_cast<int>(read_integer(t, shape_field("facets")));
  c.join = read_choice(t, shape_field("join"), {"narrow_ends", "wide_ends"}) == "narrow_ends"
               ? UpDownCone::Join::narrow_ends
               : UpDownCone::Join::wide_ends;
  return up_down_cone_shape(c, r);
}

ShapeSpec build_letter(const SceneNode& t, double r) {
  // Required of a letter (the table's default names the kind that requires it).
  const std::string letter = t.get_choice(shape_field("letter").key, {"O", "T", "Z", "K", "A", "C"});
  LetterSize size;
  size.width = read_number(t, shape_field("width"));
  Field height = shape_field("height");  // required for an up_down_cone; a letter's has a default
  height.fallback = size.height;
  size.height = read_number(t, height);
  size.depth = read_number(t, shape_field("depth"));
  size.stroke = read_number(t, shape_field("stroke"));
  return letter_shape(letter[0], size, r);
}

ShapeSpec build_shape(const SceneNode& t, const std::string& kind, double r) {
  if (kind == "box") return box_shape(to_e(t.get_vec3(shape_field("size").key)), r);
  if (kind == "triangular_prism")
    return triangular_prism_shape(read_number(t, shape_field("side")), read_number(t, shape_field("length")), r);
  if (kind == "up_down_cone") return build_up_down_cone(t, r);
  if (kind == "sphere") return spheres_shape(std::array{Eigen::Vector3d::Zero().eval()}, r);
  if (kind == "ellipsoid") return ellipsoid_shape(to_e(t.get_vec3(shape_field("semi_axes").key)), r);
  if (kind == "spheres") {
    std::vector<Eigen::Vector3d> centres;
    for (const auto& c : t.get_vec3_list(shape_field("centres").key)) centres.push_back(to_e(c));
    return spheres_shape(centres, r);
  }
  if (kind == "letter") return build_letter(t, r);
  const Field& path = shape_field("path");
  const std::filesystem::path file = t.doc().resolve(t.get_string(path.key));
  try {
    return read_shape_file(file, r);
  } catch (const ShapeFileError& e) {
    t.fail(path.key, e.what(), "correct the shape file or give another path");
  }
}

double smallest_edge(const ShapeSpec& shape) {
  const ShapeBox b = core_box(shape);
  return (b.hi - b.lo).minCoeff() + 2.0 * shape.radius;
}

BodyShape read_shape(const DemScene& s, const SceneNode& t) {
  BodyShape out;
  out.name = t.get_string(shape_field("name").key);
  out.line = t.line();
  const Field& kind_field = shape_field("kind");
  const std::string kind = read_choice(
      t, kind_field, {"box", "triangular_prism", "up_down_cone", "letter", "file", "sphere", "spheres", "ellipsoid"});
  Field radius = shape_field("radius");  // a sphere or a clump of spheres needs a radius > 0
  radius.range.lo_open = kind == "sphere" || kind == "spheres";
  const double r = read_number(t, radius);
  if (s.law == "hertz_mindlin" && r == 0.0)
    t.fail(radius.key, "a sharp shape (radius 0) has no Hertz stiffness", "give the shape a dilation radius > 0 (m)");
  const double rho = read_number(t, shape_field("density"));
  try {
    out.shape = build_shape(t, kind, r);
  } catch (const std::invalid_argument& e) {
    t.fail(kind_field.key, std::string("the ") + kind + " cannot be built: " + e.what(), "correct its dimensions or radius");
  }
  Field grid = shape_field("grid");
  if (kind == "sphere") {  // exact: no grid
    if (t.has(grid.key)) t.fail(grid.key, "a sphere's mass properties are exact, not counted on a grid", "remove grid");
    out.props = sphere_mass_properties(r, rho);
    out.bound = r;
    return out;
  }
  if (kind == "ellipsoid" && r == 0.0) {  // exact: no grid
    if (t.has(grid.key))
      t.fail(grid.key, "a sharp ellipsoid's mass properties are exact, not counted on a grid", "remove grid");
    out.props = ellipsoid_mass_properties(to_e(t.get_vec3(shape_field("semi_axes").key)), rho);
    out.bound = shape_reach(out.shape, out.props.centre);
    return out;
  }
  grid.fallback = 0.1 * smallest_edge(out.shape);  // the default the table states in words
  const double h = read_number(t, grid);
  try {
    out.props = voxel_mass_properties(shape_members(out.shape), rho, h);
  } catch (const std::invalid_argument& e) {
    t.fail(grid.key, e.what(), "give a coarser grid (m)");
  }
  if (out.props.voxels < 8)
    t.fail(grid.key, "only " + std::to_string(out.props.voxels) + " voxels lie inside the shape",
           "give a grid edge (m) well below the shape's smallest dimension");
  out.bound = shape_reach(out.shape, out.props.centre);
  return out;
}

bool empty_lattice(const std::array<std::size_t, 3>& n) { return n[0] == 0 || n[1] == 0 || n[2] == 0; }

const Field& output_field(std::string_view key) { return kBodyOutputFields.field(key); }

// A body scene's [output]: its pictures, and the frame fields a body frame always holds. The keys
// bodies share with grains (series_interval, frame_interval, the checkpoints) are read by load_dem_scene.
void read_body_output(const DemScene& s, const SceneNode& out, BodyOutputSpec& o) {
  for (const Field* f : {&output_field("picture_angles"), &output_field("picture_speed_max")})
    if (out.has(f->key))
      out.fail(f->key, "body pictures are drawn at times, not at drum angles, and coloured by group or layer",
               "remove it; use picture_interval (s) and picture_colour = \"group\", \"layer\" or \"shape\"");
  const Field& interval = output_field("picture_interval");
  o.picture_interval = read_number(out, interval);
  if (o.picture_interval > 0 && o.picture_interval < s.dt)
    out.fail(interval.key, "shorter than the time step", "use a multiple of run.dt, or 0 for no pictures");
  if (o.picture_interval > 0 && o.picture_interval < 1e-4)
    out.fail(interval.key, "pictures closer than 1e-4 s would share file names (four decimals)",
             "use an interval of at least 1e-4 s, or 0 for none");
  o.picture_size = static_cast<int>(read_integer(out, output_field("picture_size")));
  const std::string colour = read_choice(out, output_field("picture_colour"), {"group", "layer", "shape"});
  o.colour_by_layer = colour == "layer";
  o.colour_by_shape = colour == "shape";
  o.view_axis = read_choice(out, output_field("picture_view"), {"z", "x"}) == "z" ? 2 : 0;
  const Field& force = output_field("frame_force");
  if (read_bool(out, force)) out.fail(force.key, "body frames hold no forces", "remove frame_force, or set it false");
  const Field &velocity = output_field("frame_velocity"), &angular = output_field("frame_angular_velocity");
  if (!read_bool(out, velocity) || !read_bool(out, angular))
    out.fail(out.has(velocity.key) ? velocity.key : angular.key,
             "body frames always hold velocities and angular velocities (what a restart from them needs)",
             "remove the key");
}

// A body scene's [analysis]: the outlet height (m along -gravity) and the heaps of [[analysis.repose]].
void read_body_analysis(const DemScene& s, const SceneNode& an, BodyOutputSpec& o) {
  for (const char* key : {"species", "mixing_cell", "mixing_min_grains"}) {
    const Field& f = kBodyAnalysisFields.field(key);
    if (an.has(f.key))
      an.fail(f.key, "the mixing measures compare species of grains, and a body scene has none",
              "remove it; bodies take outlet_height (m) and [[analysis.repose]]");
  }
  const Field& outlet = kBodyAnalysisFields.field("outlet_height");
  o.has_outlet = an.has(outlet.key);
  if (o.has_outlet) o.outlet_height = read_number(an, outlet);
  if (an.has("repose")) {  // [[analysis.repose]]: its keys are kReposeFields
    const double g = std::sqrt(s.gravity.x * s.gravity.x + s.gravity.y * s.gravity.y + s.gravity.z * s.gravity.z);
    if (!(g > 0)) an.fail("repose", "a heap's slope is measured against gravity, and run.gravity is zero", "give run.gravity");
    o.repose = read_repose(an, {-s.gravity.x / g, -s.gravity.y / g, -s.gravity.z / g});
  }
}

// [sink]: its height (m along -gravity), below the outlet's.
void read_sink(const SceneNode& sink, BodyOutputSpec& o) {
  const Field& height = kSinkFields.field("height");
  o.has_sink = true;
  o.sink_height = read_number(sink, height);
  if (o.has_outlet && o.sink_height >= o.outlet_height)
    sink.fail(height.key, "the sink lies at or above analysis.outlet_height: bodies still in the hopper would vanish",
              "give a height below the outlet (m along -gravity)");
}

// [output], [analysis] and [sink] of a body scene (body_fields.hpp), the overlap scale, and the drum
// walls' speed against it.
void read_body_outputs(const DemScene& s, const SceneNode& root, BodiesSpec& b) {
  BodyOutputSpec& o = b.output;
  if (const auto out = root.maybe_table("output")) read_body_output(s, *out, o);
  if (const auto an = root.maybe_table("analysis")) read_body_analysis(s, *an, o);
  if (const auto sink = root.maybe_table("sink")) read_sink(*sink, o);
  // The overlap scale: the thinnest moving shape's smallest outer dimension (fixed walls and gates
  // may be thinner than any grain without tightening the grains' limit).
  o.overlap_scale = std::numeric_limits<double>::infinity();
  for (const BodyPlacement& p : b.placed)
    if (!p.fixed) o.overlap_scale = std::min(o.overlap_scale, smallest_edge(b.shapes[p.shape].shape));
  // A turning drum's mantle, and a translating wall, may move at most 0.1 of the thinnest shape per
  // step (as for grains).
  for (const SceneNode& w : root.tables("wall")) {
    const std::string type = w.get_string("type", "plane");
    if (has_wall_motion(w))
      require_motion_step(s, w, read_wall_motion(w), o.overlap_scale, "the thinnest moving shape");
    if ((type != "cylinder" && type != "drum") || !w.has("omega")) continue;
    const double step = std::abs(w.get_double("omega", Range::any())) * w.get_double("radius", Range::positive()) * s.dt;
    if (step > 0.1 * o.overlap_scale)
      w.fail("omega", "the wall's surface moves " + short_number(step) + " m per step, more than 0.1 of the thinnest "
                      "moving shape (" + short_number(o.overlap_scale) + " m)",
             "lower omega (rad/s) or run.dt");
  }
}

const Field& bodies_field(std::string_view key) { return kBodiesFields.field(key); }

std::size_t shape_index(const BodiesSpec& b, const SceneNode& t) {
  const Field& shape = bodies_field("shape");
  const std::string name = t.get_string(shape.key);
  for (std::size_t k = 0; k < b.shapes.size(); ++k)
    if (b.shapes[k].name == name) return k;
  std::string names;
  for (const BodyShape& sh : b.shapes) names += (names.empty() ? "'" : ", '") + sh.name + "'";
  t.fail(shape.key, "no [[shape]] is named '" + name + "'", "use one of the [[shape]] names: " + names);
}

std::array<double, 4> random_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  std::array<double, 4> q{n(rng), n(rng), n(rng), n(rng)};
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= len;
  return q;
}

// `count` centres on a cubic lattice in a box region, its spacing the bounding sphere's diameter
// (plus 2 %), filled row by row along x, then z, then layer by layer up the region's y axis; sites
// whose bounding sphere would meet a body placed before are skipped. A dense start that random
// placement cannot reach (it jams near a solid fraction of 0.38 of the bounding spheres); random
// orientations then make the packing irregular as it settles.
std::vector<std::array<double, 3>> lattice_positions(const SceneNode& t, const BodiesSpec& b, std::size_t shape,
                                                     const Region& region, std::size_t count) {
  if (region.kind != Region::Kind::Box)
    t.fail(bodies_field("arrangement").key, "a lattice fills a box region", "give region = { shape = \"box\", lo, hi }, or arrangement = \"random\"");
  const double bound = b.shapes[shape].bound, step = 2.02 * bound;
  std::array<std::size_t, 3> n{};
  std::array<double, 3> first{};
  for (int k = 0; k < 3; ++k) {
    const double room = region.hi[k] - region.lo[k] - 2.0 * bound;
    n[k] = room < 0 ? 0 : static_cast<std::size_t>(std::floor(room / step)) + 1;
    first[k] = 0.5 * (region.lo[k] + region.hi[k]) - 0.5 * static_cast<double>(n[k] == 0 ? 0 : n[k] - 1) * step;
  }
  if (empty_lattice(n))
    t.fail("region", "the region is narrower than one body (" + short_number(2 * bound) + " m across its bounding sphere)",
           "enlarge the region");
  first[1] = region.lo[1] + bound;  // layers from the bottom up
  std::vector<std::array<double, 3>> out;
  for (std::size_t iy = 0; iy < n[1] && out.size() < count; ++iy)
    for (std::size_t iz = 0; iz < n[2] && out.size() < count; ++iz)
      for (std::size_t ix = 0; ix < n[0] && out.size() < count; ++ix) {
        const std::array<double, 3> x{first[0] + ix * step, first[1] + iy * step, first[2] + iz * step};
        bool free = true;
        for (const BodyPlacement& p : b.placed)
          free = free && std::hypot(x[0] - p.x[0], x[1] - p.x[1], x[2] - p.x[2]) >= bound + b.shapes[p.shape].bound;
        if (free) out.push_back(x);
      }
  if (out.size() < count)
    t.fail("count", "the lattice in the region holds " + std::to_string(out.size()) + " of the " + std::to_string(count) +
                        " bodies (" + std::to_string(n[0]) + " x " + std::to_string(n[2]) + " per layer, " +
                        std::to_string(n[1]) + " layers of " + short_number(step) + " m)",
           "raise the region's hi[1] to at least " + short_number(region.lo[1] + static_cast<double>(
               (count + n[0] * n[2] - 1) / (n[0] * n[2])) * step + bound) + " m, or lower the count");
  return out;
}

std::vector<std::array<double, 3>> random_positions(const DemScene& s, const SceneNode& t, const BodiesSpec& b,
                                                    std::size_t shape, std::uint64_t seed) {
  const Region region = read_fill_region(t, s.gravity);
  const auto count = static_cast<std::size_t>(read_integer(t, bodies_field("count")));
  if (read_choice(t, bodies_field("arrangement"), {"random", "lattice"}) == "lattice")
    return lattice_positions(t, b, shape, region, count);
  std::vector<PlacedGrain> existing;
  for (const BodyPlacement& p : b.placed) existing.push_back({p.x, 0, b.shapes[p.shape].bound});
  try {
    std::vector<std::array<double, 3>> out;
    for (const PlacedGrain& g : place_random(region, {{0, b.shapes[shape].bound, count}}, seed, existing))
      out.push_back(g.x);
    return out;
  } catch (const FillError& e) {
    t.fail("count", e.what(), "lower the count or enlarge the region");
  }
}

// The moving bodies of shape `name` in a body frame file (body_outputs.hpp: the CSV a run writes per
// frame), each with its centre of mass, orientation of the shape's frame, velocity and angular
// velocity: a run restarted from a frame's state.
std::vector<BodyPlacement> frame_file_placements(const SceneNode& t, std::size_t shape, const std::string& name) {
  const std::filesystem::path file = t.doc().resolve(t.get_string(bodies_field("file").key));
  std::string text;
  FileProblem why;
  if (!read_regular_file(file, std::size_t(1) << 30, text, why)) t.fail("file", why.problem, why.fix);
  const std::string header = "id,shape,group,layer,motion,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
  std::istringstream in(text);
  std::string line;
  if (!std::getline(in, line) || line != header)
    t.fail("file", shown_path(file.string()) + " does not start with the body frame header '" + header + "'",
           "give a frames/frame_NNNNNN.csv that grainflow run wrote");
  std::vector<BodyPlacement> out;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::istringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    auto bad = [&](const std::string& what) {
      t.fail("file", shown_path(file.string()) + ":" + std::to_string(number) + ": " + what,
             "give a frame file that grainflow run wrote, unchanged");
    };
    if (f.size() != 18) bad("expected 18 fields, found " + std::to_string(f.size()));
    if (f[1] != name || f[4] != "moving") continue;
    double v[13];
    for (int k = 0; k < 13; ++k) {
      const std::string& x = f[static_cast<std::size_t>(5 + k)];
      char* end = nullptr;
      v[k] = std::strtod(x.c_str(), &end);
      if (x.empty() || *end != '\0' || !std::isfinite(v[k])) bad("field " + std::to_string(6 + k) + " is not a finite number");
    }
    const double qq = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5] + v[6] * v[6]);
    if (std::abs(qq - 1.0) > 1e-6) bad("the quaternion is not of unit length");
    BodyPlacement p;
    p.shape = shape;
    p.line = t.line();
    p.x = {v[0], v[1], v[2]};
    p.q = {v[3], v[4], v[5], v[6]};
    p.v = {v[7], v[8], v[9]};
    p.w = {v[10], v[11], v[12]};
    out.push_back(p);
  }
  if (out.empty())
    t.fail("file", shown_path(file.string()) + " holds no moving body of shape '" + name + "'",
           "give the frame of a run with this shape, or another [[shape]]");
  return out;
}

// `remove_at` (s of the main stage), or -1 when the bodies stay.
double read_remove_at(const SceneNode& t) {
  const Field& f = bodies_field("remove_at");
  return t.has(f.key) ? read_number(t, f) : -1.0;
}

void read_placements(const DemScene& s, const SceneNode& t, std::size_t index, BodiesSpec& b) {
  const std::size_t shape = shape_index(b, t);
  Field group_field = bodies_field("group");
  group_field.fallback = static_cast<double>(index);  // the default the table states in words
  const int group = static_cast<int>(read_integer(t, group_field));
  if (t.has(bodies_field("file").key)) {
    for (const char* key : {"positions", "count", "orientation", "velocity", "fixed"})
      if (t.has(bodies_field(key).key))
        t.fail(key, "the bodies of a frame file take their state from it", std::string("remove ") + key + ", or file");
    const std::vector<BodyPlacement> placed = frame_file_placements(t, shape, b.shapes[shape].name);
    const double remove_at = read_remove_at(t);
    for (BodyPlacement p : placed) {
      p.group = group;
      p.remove_at = remove_at;
      b.placed.push_back(p);
    }
    return;
  }
  const Field& positions = bodies_field("positions");
  if (t.has(positions.key) == t.has(bodies_field("count").key))
    t.fail(positions.key, "give exactly one of 'positions', 'count' (with a region) and 'file' (a body frame)",
           "e.g. positions = [[0, 0.1, 0]] or count = 10 with region = { shape = \"box\", lo, hi }");
  const auto seed = static_cast<std::uint64_t>(t.get_int(
      bodies_field("seed").key, static_cast<std::int64_t>(s.seed + index), 0, std::numeric_limits<std::int64_t>::max()));
  const auto xs = t.has(positions.key) ? t.get_vec3_list(positions.key) : random_positions(s, t, b, shape, seed);
  const bool random = read_choice(t, bodies_field("orientation"), {"identity", "random"}) == "random";
  const bool fixed = read_bool(t, bodies_field("fixed"));
  const Field& velocity = bodies_field("velocity");
  const auto v = t.get_vec3(velocity.key, {0, 0, 0});
  if (fixed && (v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0))
    t.fail(velocity.key, "a fixed body never moves", "remove velocity, or fixed = true");
  const double remove_at = read_remove_at(t);
  std::mt19937_64 rng(seed);
  for (const auto& x : xs) {
    BodyPlacement p{shape, t.line(), fixed, remove_at, group, x, {1.0, 0.0, 0.0, 0.0}, v, {0.0, 0.0, 0.0}};
    if (random) p.q = random_quaternion(rng);
    b.placed.push_back(p);
  }
}

// The body as the step check sees it: its own mass, or (rim) the mass a contact at its rim meets.
template <class L>
ContactBody<typename L::Material> shape_body(const BodyShape& sh, const typename L::Material& m, bool rim = false) {
  return {rim ? rim_mass(sh) : sh.props.mass, sh.props.moments.minCoeff(), sh.shape.radius, m, false};
}

// One material for every body (BodyContactModel): read from each shape, which must agree.
template <class L>
typename L::Material read_material(const std::vector<SceneNode>& shapes) {
  const typename L::Material m = L::read_material(shapes.front());
  for (std::size_t k = 1; k < shapes.size(); ++k) {
    const typename L::Material other = L::read_material(shapes[k]);
    if constexpr (!std::is_empty_v<typename L::Material>)
      if (std::memcmp(&m, &other, sizeof m) != 0)
        shapes[k].fail("youngs_modulus", "bodies (and the spheres among them) share one material, and this table states another",
                       "give every [[shape]] and [[species]] the first one's youngs_modulus and poisson_ratio");
  }
  return m;
}

template <class L>
void read_model(const SceneNode& root, const std::vector<SceneNode>& nodes, BodiesSpec& b) {
  const SceneNode ct = root.table("contact");
  BodyContactModel<L> model;
  model.material = read_material<L>(nodes);
  model.pair = L::read_params(ct, nullptr, false);
  const auto wall = ct.maybe_table("wall");
  model.wall = wall ? L::read_params(*wall, &model.pair, true) : model.pair;
  ContactBody<typename L::Material> plane;
  plane.wall = true;
  for (const bool rim : {false, true}) {
    CriticalStep& into = rim ? b.rim : b.critical;
    into = {std::numeric_limits<double>::infinity(), ""};
    auto consider = [&](const std::vector<StepTerm>& terms, const std::string& who) {
      for (const StepTerm& t : terms)
        if (t.time < into.period) into = {t.time, t.term + ", " + who};
    };
    for (const BodyShape& a : b.shapes) {
      for (const BodyShape& c : b.shapes)
        consider(L::critical_terms(shape_body<L>(a, model.material, rim), shape_body<L>(c, model.material, rim),
                                   model.pair),
                 a.name + "-" + c.name);
      consider(L::critical_terms(shape_body<L>(a, model.material, rim), plane, model.wall), a.name + "-wall");
    }
  }
  b.install_model = [model](World& w) { w.resources.emplace<BodyContactModel<L>>(model); };
  b.schedule_contacts = [](Schedule& step) { step.emplace<BodyContact<L>>(); };
}

}  // namespace

double rim_mass(const BodyShape& sh) {
  const Eigen::Matrix3d inverse = sh.props.inertia.inverse();
  double worst = 0;  // the largest (r x n)^T I^-1 (r x n) over the vertices r and the unit n
  for (const DilatedPolyhedron& member : shape_members(sh.shape))
    for (const Eigen::Vector3d& v : member.vertices) {
      const Eigen::Vector3d r = v - sh.props.centre;
      Eigen::Matrix3d cross;  // cross * n = r x n
      cross << 0, -r.z(), r.y(), r.z(), 0, -r.x(), -r.y(), r.x(), 0;
      const Eigen::Matrix3d m = cross.transpose() * inverse * cross;
      worst = std::max(worst, Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(m).eigenvalues().maxCoeff());
    }
  return 1.0 / (1.0 / sh.props.mass + worst);
}

bool scene_has_bodies(const SceneNode& root) { return !root.tables("bodies").empty(); }

void require_body_scene(const SceneNode& root) {
  const std::string why = "composite grains do not share a scene with it yet";
  require_species_with_bodies(root);
  for (const char* key : {"feed", "outlet"})
    if (!root.tables(key).empty())
      root.fail(key, std::string("[[") + key + "]]: " + why, "place spheres with a [[fill]], or remove the [[bodies]] tables");
  for (const char* key : {"periodic"})
    if (root.has(key)) root.fail(key, std::string("[") + key + "]: " + why, "remove it, or the [[bodies]] tables");
  for (const SceneNode& w : root.tables("wall")) {
    const std::string type = w.get_choice("type", {"plane", "box", "cylinder", "drum", "mesh"});
    if (type == "mesh") w.fail("type", "bodies do not meet mesh walls yet", "use plane, box, cylinder or drum walls");
    // A turning plane keeps its place only when it turns about its own normal (a drum's end plate).
    if (type == "plane" && w.has("omega") && w.get_double("omega", Range::any()) != 0.0 && w.has("rotation_axis")) {
      const auto n = w.get_vec3("normal"), a = w.get_vec3("rotation_axis");
      const Eigen::Vector3d cross = Eigen::Vector3d(n[0], n[1], n[2]).cross(Eigen::Vector3d(a[0], a[1], a[2]));
      if (cross.norm() > 1e-9 * Eigen::Vector3d(n[0], n[1], n[2]).norm() * Eigen::Vector3d(a[0], a[1], a[2]).norm())
        w.fail("rotation_axis", "a plane turning about another axis than its normal sweeps through the bodies, "
                                "which meet only walls whose surface stays in place",
               "turn the plane about its normal, or remove omega");
    }
  }
}

BodiesSpec read_bodies(const DemScene& s, const SceneNode& root) {
  BodiesSpec b;
  std::vector<SceneNode> shapes = root.tables("shape");
  if (shapes.empty() && s.species.empty())
    root.fail("shape", "the [[bodies]] name no shape", "add a [[shape]] table with name and kind");
  const std::string_view name = shape_field("name").key;
  for (const SceneNode& t : shapes) {
    for (const BodyShape& other : b.shapes)
      if (other.name == t.get_string(name)) t.fail(name, "shape '" + other.name + "' is defined twice", "rename one");
    b.shapes.push_back(read_shape(s, t));
  }
  add_species_shapes(s, root, b);
  const std::vector<SceneNode> tables = root.tables("bodies");
  b.line = tables.front().line();
  for (std::size_t k = 0; k < tables.size(); ++k) read_placements(s, tables[k], k, b);
  place_fill_spheres(s, b, static_cast<int>(tables.size()));
  bool moving = false;
  for (const BodyPlacement& p : b.placed) moving = moving || !p.fixed;
  if (!moving) tables.front().fail(bodies_field("fixed").key, "every body is fixed: nothing would move", "leave some [[bodies]] moving");
  for (const SceneNode& sp : root.tables("species")) shapes.push_back(sp);  // their materials, as the shapes'
  with_law(s.law, [&]<class L>() { read_model<L>(root, shapes, b); });
  read_body_outputs(s, root, b);
  return b;
}

namespace {

// Removes the [[bodies]] with remove_at once the main stage reaches that time (never while settling
// or priming). Idempotent, so it needs no state of its own: a resumed run finds them removed.
class TimedBodyRemoval : public SystemBase<TimedBodyRemoval> {
 public:
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<BodyMotion, BodyVelocity, BodyAngularVelocity, BodyForce, BodyTorque>;
  explicit TimedBodyRemoval(std::vector<std::pair<double, std::uint32_t>> rows) : rows_(std::move(rows)) {}
  std::string_view name() const override { return "timed_body_removal"; }
  void run(World& world, const StepContext& step) override {
    if (step.prime || step.stage == "settle") return;
    Bodies& b = world.tables.get<Bodies>();
    // The step that starts at t >= remove_at (to half a step's round-off) runs without them.
    for (const auto& [t, row] : rows_)
      if (step.t >= t - 0.5 * step.dt && b.motion.state[row] != static_cast<std::uint8_t>(Motion::removed))
        remove_body(b, row);
  }

 private:
  std::vector<std::pair<double, std::uint32_t>> rows_;
};

// Removes moving bodies whose centre of mass fell below the sink's height (along -gravity).
class BodySink : public SystemBase<BodySink> {
 public:
  using Reads = gf::Reads<BodyPosition, Gravity>;
  using Writes = gf::Writes<BodyMotion, BodyVelocity, BodyAngularVelocity, BodyForce, BodyTorque>;
  explicit BodySink(double height) : height_(height) {}
  std::string_view name() const override { return "body_sink"; }
  void run(World& world, const StepContext& step) override {
    if (step.prime) return;
    Bodies& b = world.tables.get<Bodies>();
    const Gravity& g = world.resources.get<Gravity>();
    const double gn = std::sqrt(g.x * g.x + g.y * g.y + g.z * g.z);
    if (gn == 0.0) return;
    for (std::size_t i = 0; i < b.n; ++i)
      if (b.moving(i) && -(g.x * b.pos.x[i] + g.y * b.pos.y[i] + g.z * b.pos.z[i]) / gn < height_) remove_body(b, i);
  }

 private:
  double height_;
};

[[noreturn]] void body_error(const DemScene& s, const BodyPlacement& p, const std::string& what) {
  throw SceneError(s.file.string() + ":" + std::to_string(p.line) + ": " + what);
}

void push_body(const DemScene& s, const BodyPlacement& p, Bodies& bodies, Members& members) {
  const BodyShape& sh = s.bodies->shapes[p.shape];
  const Eigen::Quaterniond frame(p.q[0], p.q[1], p.q[2], p.q[3]);
  BodyRow row = body_row(sh.props, to_e(p.x), frame);
  row.v = p.v;
  row.w = p.w;
  if (p.fixed) row.motion = Motion::fixed;
  const auto body = static_cast<std::uint32_t>(bodies.push(row));
  for (const MemberRow& m : body_frame_members(shape_members(sh.shape), sh.props, body)) members.push(m);
}

// A body whose centre of mass lies behind a wall starts outside the domain.
void require_inside(const DemScene& s, const BodyPlacement& p) {
  for (const Wall& w : s.walls) {
    Vec3d n;
    if (wall_gap(w, {p.x[0], p.x[1], p.x[2]}, n) <= 0.0)
      body_error(s, p, "[[bodies]]: a body's centre (" + short_number(p.x[0]) + ", " + short_number(p.x[1]) + ", " +
                           short_number(p.x[2]) + ") m is behind wall '" + w.name +
                           "'. Fix: move it inside the walls");
  }
}

}  // namespace

void build_body_world(const DemScene& s, World& world) {
  Bodies& bodies = world.tables.add<Bodies>();
  Members& members = world.tables.add<Members>();
  for (const BodyPlacement& p : s.bodies->placed) {
    if (!p.fixed) require_inside(s, p);
    push_body(s, p, bodies, members);
  }
  place_members(bodies, members);
  BodyPlanes& planes = world.resources.emplace<BodyPlanes>();
  const auto e = [](const Vec3d& v) { return Eigen::Vector3d(v.x, v.y, v.z); };
  for (const Wall& w : s.walls) {
    BodyPlane b;
    b.cylinder = w.kind == Wall::Kind::CylinderInner;
    b.point = e(b.cylinder ? w.center : w.point);
    b.normal = e(b.cylinder ? w.axis : w.normal);
    b.radius = w.radius;
    b.omega = w.omega;
    b.rot_point = e(w.rot_point);
    b.rot_axis = e(w.rot_axis);
    b.motion = w.motion;
    planes.list.push_back(b);
  }
  BodyContactState& state = world.resources.emplace<BodyContactState>();
  state.skin = s.skin;
  state.overlap_limit = s.max_overlap * s.bodies->output.overlap_scale;
  s.bodies->install_model(world);
}

void schedule_body_step(Schedule& step, const DemScene& s) {
  std::vector<std::pair<double, std::uint32_t>> timed;
  for (std::size_t i = 0; i < s.bodies->placed.size(); ++i)
    if (s.bodies->placed[i].remove_at >= 0) timed.push_back({s.bodies->placed[i].remove_at, static_cast<std::uint32_t>(i)});
  if (!timed.empty()) step.emplace<TimedBodyRemoval>(std::move(timed));
  if (s.bodies->output.has_sink) step.emplace<BodySink>(s.bodies->output.sink_height);
  step.emplace<IntegrateBodyPositions>();
  step.emplace<PlaceMembers>();
  s.bodies->schedule_contacts(step);
  step.emplace<IntegrateBodyVelocities>();
}

}  // namespace gf
