#include "systems/setup/body_sphere_fill.hpp"

#include <cmath>
#include <string>

#include "systems/bodies/mass_properties.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

namespace {

// The shape of species sp (add_species_shapes put them after the [[shape]] tables, in order).
std::size_t species_shape(const DemScene& s, const BodiesSpec& b, std::int32_t sp) {
  return b.shapes.size() - s.species.size() + static_cast<std::size_t>(sp);
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
    if (!sp.size.is_fixed())
      nodes[k].fail("diameter", "species '" + sp.name + "' has a size distribution, and among composite bodies a species is "
                                "one sphere shape",
                    "give the species one diameter (m)");
    const double r = 0.5 * sp.smallest();
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
  // A fill keeps clear of the bodies' bounding spheres and of the spheres of the fills before it.
  std::vector<PlacedGrain> existing;
  for (const BodyPlacement& p : b.placed) existing.push_back({p.x, 0, b.shapes[p.shape].bound});
  for (std::size_t k = 0; k < s.fills.size(); ++k) {
    const std::vector<PlacedGrain> spheres = place_fill(s, s.fills[k], existing);
    for (const PlacedGrain& g : spheres) {
      BodyPlacement p;
      p.shape = species_shape(s, b, g.type);
      p.line = s.fills[k].line;
      p.group = first_group + static_cast<int>(k);
      p.x = g.x;
      p.v = g.v;
      p.w = g.w;
      b.placed.push_back(p);
    }
    existing.insert(existing.end(), spheres.begin(), spheres.end());
  }
}

}  // namespace gf
