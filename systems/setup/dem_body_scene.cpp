#include "systems/setup/dem_body_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstring>
#include <random>
#include <type_traits>

#include "systems/analysis/metrics.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/bodies/body_integrate.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/laws.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/setup/dem_scene.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

namespace {

Eigen::Vector3d to_e(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

ShapeSpec build_shape(const SceneNode& t, const std::string& kind, double r) {
  if (kind == "box") return box_shape(to_e(t.get_vec3("size")), r);
  if (kind == "triangular_prism")
    return triangular_prism_shape(t.get_double("side", Range::positive()), t.get_double("length", Range::positive()), r);
  if (kind == "up_down_cone") {
    UpDownCone c;
    c.base_radius = t.get_double("base_radius", Range::positive());
    c.neck_radius = t.get_double("neck_radius", Range::non_negative());
    c.height = t.get_double("height", Range::positive());
    c.facets = static_cast<int>(t.get_int("facets", 12, 3, static_cast<std::int64_t>(kMaxCoreVertices / 2)));
    c.join = t.get_choice("join", {"narrow_ends", "wide_ends"}, "narrow_ends") == "narrow_ends"
                 ? UpDownCone::Join::narrow_ends
                 : UpDownCone::Join::wide_ends;
    return up_down_cone_shape(c, r);
  }
  if (kind == "letter") {
    const std::string letter = t.get_choice("letter", {"O", "T", "Z", "K", "A", "C"});
    LetterSize size;
    size.width = t.get_double("width", size.width, Range::positive());
    size.height = t.get_double("height", size.height, Range::positive());
    size.depth = t.get_double("depth", size.depth, Range::positive());
    size.stroke = t.get_double("stroke", size.stroke, Range::positive());
    return letter_shape(letter[0], size, r);
  }
  const std::filesystem::path file = t.doc().resolve(t.get_string("path"));
  try {
    return read_shape_file(file, r);
  } catch (const ShapeFileError& e) {
    t.fail("path", e.what(), "correct the shape file or give another path");
  }
}

double smallest_edge(const ShapeSpec& shape) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& part : shape.parts)
    for (const Eigen::Vector3d& v : part) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return (hi - lo).minCoeff() + 2.0 * shape.radius;
}

double bound_radius(const ShapeSpec& shape, const Eigen::Vector3d& centre) {
  double b = 0.0;
  for (const auto& part : shape.parts)
    for (const Eigen::Vector3d& v : part) b = std::max(b, (v - centre).norm());
  return b + shape.radius;
}

BodyShape read_shape(const DemScene& s, const SceneNode& t) {
  BodyShape out;
  out.name = t.get_string("name");
  out.line = t.line();
  const std::string kind = t.get_choice("kind", {"box", "triangular_prism", "up_down_cone", "letter", "file"});
  const double r = t.get_double("radius", Range::closed(0, 100));
  if (s.law == "hertz_mindlin" && r == 0.0)
    t.fail("radius", "a sharp shape (radius 0) has no Hertz stiffness", "give the shape a dilation radius > 0 (m)");
  const double rho = t.get_double("density", Range::open_closed(0, 1e6));
  try {
    out.shape = build_shape(t, kind, r);
  } catch (const std::invalid_argument& e) {
    t.fail("kind", std::string("the ") + kind + " cannot be built: " + e.what(), "correct its dimensions or radius");
  }
  const double h = t.get_double("grid", 0.1 * smallest_edge(out.shape), Range::positive());
  try {
    out.props = voxel_mass_properties(shape_members(out.shape), rho, h);
  } catch (const std::invalid_argument& e) {
    t.fail("grid", e.what(), "give a coarser grid (m)");
  }
  if (out.props.voxels < 8)
    t.fail("grid", "only " + std::to_string(out.props.voxels) + " voxels lie inside the shape",
           "give a grid edge (m) well below the shape's smallest dimension");
  out.bound = bound_radius(out.shape, out.props.centre);
  return out;
}

std::size_t shape_index(const BodiesSpec& b, const SceneNode& t) {
  const std::string name = t.get_string("shape");
  for (std::size_t k = 0; k < b.shapes.size(); ++k)
    if (b.shapes[k].name == name) return k;
  std::string names;
  for (const BodyShape& sh : b.shapes) names += (names.empty() ? "'" : ", '") + sh.name + "'";
  t.fail("shape", "no [[shape]] is named '" + name + "'", "use one of the [[shape]] names: " + names);
}

std::array<double, 4> random_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  std::array<double, 4> q{n(rng), n(rng), n(rng), n(rng)};
  const double len = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= len;
  return q;
}

std::vector<std::array<double, 3>> random_positions(const DemScene& s, const SceneNode& t, const BodiesSpec& b,
                                                    std::size_t shape, std::uint64_t seed) {
  const Region region = read_fill_region(t, s.gravity);
  const auto count = static_cast<std::size_t>(t.get_int("count", 1, 100000));
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

void read_placements(const DemScene& s, const SceneNode& t, std::size_t index, BodiesSpec& b) {
  const std::size_t shape = shape_index(b, t);
  if (t.has("positions") == t.has("count"))
    t.fail("positions", "give exactly one of 'positions' and 'count' (with a region)",
           "e.g. positions = [[0, 0.1, 0]] or count = 10 with region = { shape = \"box\", lo, hi }");
  const auto seed = static_cast<std::uint64_t>(
      t.get_int("seed", static_cast<std::int64_t>(s.seed + index), 0, std::numeric_limits<std::int64_t>::max()));
  const auto xs = t.has("positions") ? t.get_vec3_list("positions") : random_positions(s, t, b, shape, seed);
  const bool random = t.get_choice("orientation", {"identity", "random"}, "identity") == "random";
  const auto v = t.get_vec3("velocity", {0, 0, 0});
  std::mt19937_64 rng(seed);
  for (const auto& x : xs) {
    BodyPlacement p{shape, t.line(), x, {1.0, 0.0, 0.0, 0.0}, v};
    if (random) p.q = random_quaternion(rng);
    b.placed.push_back(p);
  }
}

template <class L>
ContactBody<typename L::Material> shape_body(const BodyShape& sh, const typename L::Material& m) {
  return {sh.props.mass, sh.props.moments.minCoeff(), sh.shape.radius, m, false};
}

// One material for every body (BodyContactModel): read from each shape, which must agree.
template <class L>
typename L::Material read_material(const std::vector<SceneNode>& shapes) {
  const typename L::Material m = L::read_material(shapes.front());
  for (std::size_t k = 1; k < shapes.size(); ++k) {
    const typename L::Material other = L::read_material(shapes[k]);
    if constexpr (!std::is_empty_v<typename L::Material>)
      if (std::memcmp(&m, &other, sizeof m) != 0)
        shapes[k].fail("youngs_modulus", "bodies share one material, and this shape states another",
                       "give every [[shape]] the first shape's youngs_modulus and poisson_ratio");
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
  b.critical = {std::numeric_limits<double>::infinity(), ""};
  ContactBody<typename L::Material> plane;
  plane.wall = true;
  auto consider = [&](const std::vector<StepTerm>& terms, const std::string& who) {
    for (const StepTerm& t : terms)
      if (t.time < b.critical.period) b.critical = {t.time, t.term + ", " + who};
  };
  for (const BodyShape& a : b.shapes) {
    for (const BodyShape& c : b.shapes)
      consider(L::critical_terms(shape_body<L>(a, model.material), shape_body<L>(c, model.material), model.pair),
               a.name + "-" + c.name);
    consider(L::critical_terms(shape_body<L>(a, model.material), plane, model.wall), a.name + "-wall");
  }
  b.install_model = [model](World& w) { w.resources.emplace<BodyContactModel<L>>(model); };
  b.schedule_contacts = [](Schedule& step) { step.emplace<BodyContact<L>>(); };
}

}  // namespace

bool scene_has_bodies(const SceneNode& root) { return !root.tables("bodies").empty(); }

void require_body_scene(const SceneNode& root) {
  const std::string why = "composite grains do not share a scene with it yet";
  for (const char* key : {"species", "fill"})
    if (!root.tables(key).empty())
      root.fail(key, std::string("[[") + key + "]] describes spheres: " + why, "remove it, or the [[bodies]] tables");
  for (const char* key : {"periodic", "output", "analysis"})
    if (root.has(key)) root.fail(key, std::string("[") + key + "]: " + why, "remove it, or the [[bodies]] tables");
  for (const SceneNode& w : root.tables("wall")) {
    const std::string type = w.get_choice("type", {"plane", "box", "cylinder", "drum"});
    if (type != "plane" && type != "box")
      w.fail("type", "bodies meet plane and box walls only, not a " + type, "use plane or box walls");
    if (w.has("omega") && w.get_double("omega", Range::any()) != 0.0)
      w.fail("omega", "bodies meet static walls only", "remove omega");
  }
}

BodiesSpec read_bodies(const DemScene& s, const SceneNode& root) {
  BodiesSpec b;
  const std::vector<SceneNode> shapes = root.tables("shape");
  if (shapes.empty()) root.fail("shape", "the [[bodies]] name no shape", "add a [[shape]] table with name and kind");
  for (const SceneNode& t : shapes) {
    for (const BodyShape& other : b.shapes)
      if (other.name == t.get_string("name")) t.fail("name", "shape '" + other.name + "' is defined twice", "rename one");
    b.shapes.push_back(read_shape(s, t));
  }
  const std::vector<SceneNode> tables = root.tables("bodies");
  b.line = tables.front().line();
  for (std::size_t k = 0; k < tables.size(); ++k) read_placements(s, tables[k], k, b);
  with_law(s.law, [&]<class L>() { read_model<L>(root, shapes, b); });
  return b;
}

namespace {

[[noreturn]] void body_error(const DemScene& s, const BodyPlacement& p, const std::string& what) {
  throw SceneError(s.file.string() + ":" + std::to_string(p.line) + ": " + what);
}

void push_body(const DemScene& s, const BodyPlacement& p, Bodies& bodies, Members& members) {
  const BodyShape& sh = s.bodies->shapes[p.shape];
  const Eigen::Quaterniond frame(p.q[0], p.q[1], p.q[2], p.q[3]);
  BodyRow row = body_row(sh.props, to_e(p.x), frame);
  row.v = p.v;
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
    require_inside(s, p);
    push_body(s, p, bodies, members);
  }
  place_members(bodies, members);
  BodyPlanes& planes = world.resources.emplace<BodyPlanes>();
  for (const Wall& w : s.walls)
    planes.list.push_back({{w.point.x, w.point.y, w.point.z}, {w.normal.x, w.normal.y, w.normal.z}});
  world.resources.emplace<BodyContactState>().skin = s.skin;
  s.bodies->install_model(world);
}

void schedule_body_step(Schedule& step, const DemScene& s) {
  step.emplace<IntegrateBodyPositions>();
  step.emplace<PlaceMembers>();
  s.bodies->schedule_contacts(step);
  step.emplace<IntegrateBodyVelocities>();
}

}  // namespace gf
