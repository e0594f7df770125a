#include "systems/setup/body_sphere_fill.hpp"

#include <cmath>
#include <string>

#include "systems/bodies/mass_properties.hpp"
#include "systems/fill/random_fill.hpp"
#include "systems/fill/state_csv.hpp"
#include "systems/setup/dem_scene.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

namespace {

[[noreturn]] void fail_at(const DemScene& s, const FillSpec& f, const std::string& what) {
  throw SceneError(s.file.string() + ":" + std::to_string(f.line) + ": " + f.where + ": " + what);
}

// The shape of species sp (add_species_shapes put them after the [[shape]] tables, in order).
std::size_t species_shape(const DemScene& s, const BodiesSpec& b, std::int32_t sp) {
  return b.shapes.size() - s.species.size() + static_cast<std::size_t>(sp);
}

// A sphere of this fill must start clear of every wall (a region reaching through one is a scene error).
void require_clear_of_walls(const DemScene& s, const FillSpec& f, const std::array<double, 3>& x, double r) {
  for (const Wall& w : s.walls) {
    Vec3d n;
    if (wall_gap(w, {x[0], x[1], x[2]}, n) < r)
      fail_at(s, f, "the region reaches through wall '" + w.name + "' (a sphere at (" + short_number(x[0]) + ", " +
                        short_number(x[1]) + ", " + short_number(x[2]) + ") m overlaps it). Fix: shrink the region to lie "
                        "inside the walls by at least the largest radius");
  }
}

std::vector<PlacedGrain> random_spheres(const DemScene& s, const FillSpec& f, const BodiesSpec& b) {
  std::vector<PlacedGrain> existing;
  for (const BodyPlacement& p : b.placed) existing.push_back({p.x, 0, b.shapes[p.shape].bound});
  std::vector<FillSpecies> req;
  for (const auto& [sp, count] : f.counts) req.push_back({sp, 0.5 * s.species[static_cast<std::size_t>(sp)].diameter, count});
  std::vector<PlacedGrain> out;
  try {
    out = place_random(f.region, req, f.seed, existing);
  } catch (const FillError& e) {
    fail_at(s, f, std::string(e.what()) + " (among the bodies' bounding spheres)");
  }
  for (const PlacedGrain& p : out) require_clear_of_walls(s, f, p.x, p.radius);
  return out;
}

std::vector<PlacedGrain> file_spheres(const DemScene& s, const FillSpec& f) {
  std::vector<StateRow> rows;
  try {
    rows = read_state_csv(f.path);
  } catch (const StateCsvError& e) {
    fail_at(s, f, e.what());
  }
  std::vector<PlacedGrain> out;
  for (const StateRow& r : rows) {
    std::int32_t sp = -1;
    for (const auto& [t, idx] : f.type_map)
      if (t == r.type) sp = idx;
    const std::string at = f.path.string() + ":" + std::to_string(r.line) + ": ";
    if (sp < 0)
      fail_at(s, f, at + "type " + std::to_string(r.type) + " is not mapped to a species. Fix: add it to the fill's 'types' table");
    const double d = s.species[static_cast<std::size_t>(sp)].diameter;
    if (std::abs(r.diameter - d) > 1e-9 * d)
      fail_at(s, f, at + "diameter " + short_number(r.diameter) + " m does not match species '" +
                        s.species[static_cast<std::size_t>(sp)].name + "' (" + short_number(d) +
                        " m). Fix: map the type to a species of that diameter");
    for (const Wall& w : s.walls) {
      Vec3d n;
      if (wall_gap(w, {r.x[0], r.x[1], r.x[2]}, n) <= 0.0)
        fail_at(s, f, at + "the sphere's centre is outside wall '" + w.name + "'. Fix: move it inside the walls");
    }
    out.push_back({r.x, sp, 0.5 * d, r.v, r.w});
  }
  if (out.empty()) fail_at(s, f, f.path.string() + ": the state file holds no grains. Fix: give a file with rows, or remove the fill");
  return out;
}

}  // namespace

void require_species_with_bodies(const SceneNode& root) {
  for (const SceneNode& sp : root.tables("species"))
    if (sp.has("rotates") && !sp.get_bool("rotates", true))
      sp.fail("rotates", "a species among bodies is stepped as a body, and a body always rotates",
              "remove rotates = false, or the [[bodies]] tables");
  if (const auto ct = root.maybe_table("contact"); ct && !ct->tables("pair").empty())
    ct->tables("pair").front().fail("species_a", "bodies and the spheres among them share one set of contact parameters",
                                    "remove the [[contact.pair]] tables, or the [[bodies]] tables");
}

void add_species_shapes(const DemScene& s, const SceneNode& root, BodiesSpec& b) {
  const std::vector<SceneNode> nodes = root.tables("species");
  for (std::size_t k = 0; k < s.species.size(); ++k) {
    const SpeciesSpec& sp = s.species[k];
    for (const BodyShape& other : b.shapes)
      if (other.name == sp.name)
        nodes[k].fail("name", "species '" + sp.name + "' has the name of a [[shape]], and becomes a sphere shape among bodies",
                      "rename the species or the shape");
    const double r = 0.5 * sp.diameter;
    BodyShape sh;
    sh.name = sp.name;
    sh.line = nodes[k].line();
    sh.shape = spheres_shape(std::array{Eigen::Vector3d::Zero().eval()}, r);
    sh.props = sphere_mass_properties(r, sp.density);
    sh.bound = r;
    b.shapes.push_back(std::move(sh));
  }
}

void place_fill_spheres(const DemScene& s, BodiesSpec& b, int first_group) {
  for (std::size_t k = 0; k < s.fills.size(); ++k) {
    const FillSpec& f = s.fills[k];
    const std::vector<PlacedGrain> spheres = f.kind == FillSpec::Kind::Random ? random_spheres(s, f, b) : file_spheres(s, f);
    for (const PlacedGrain& g : spheres) {
      BodyPlacement p;
      p.shape = species_shape(s, b, g.type);
      p.line = f.line;
      p.group = first_group + static_cast<int>(k);
      p.x = g.x;
      p.v = g.v;
      p.w = g.w;
      b.placed.push_back(p);
    }
  }
}

}  // namespace gf
