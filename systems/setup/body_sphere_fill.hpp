// The grain tables' spheres in a scene with composite bodies: [[species]] and [[fill]] (random in a
// region, or a state file) place spheres among the [[bodies]], each a body of one point member (the
// [[shape]] kind = "sphere": exact mass and moments, a sphere's contact with every member and wall),
// stepped with the bodies at a body's cost.
//
// Each species becomes a sphere shape of its name, diameter and density; bodies share one contact
// material, so under hertz_mindlin a species' youngs_modulus and poisson_ratio must equal the
// shapes'. The fills are placed as the grain tables' are (place_fill in dem_scene.hpp, with its
// checks and messages), after every [[bodies]] table: a random fill's spheres clear of the bodies'
// bounding spheres, of earlier fills' spheres and of the walls; a file fill takes positions,
// velocities and spins from the state CSV. A fill's spheres form one group (pictures, frames): the number of [[bodies]]
// tables plus the fill's index. Refused with bodies: species that do not rotate (a body always
// rotates) and [[contact.pair]] (one parameter set for all bodies).
#pragma once

#include "engine/scene.hpp"
#include "systems/setup/dem_body_scene.hpp"

namespace gf {

// Refuses the species and contact keys bodies cannot honour (call before the species are read).
void require_species_with_bodies(const SceneNode& root);

// Appends a sphere shape per species of `s` to b.shapes (a name taken by a [[shape]] is refused), so
// that [[bodies]] may also place them by name.
void add_species_shapes(const DemScene& s, const SceneNode& root, BodiesSpec& b);

// Appends the spheres of s.fills to b.placed (after add_species_shapes; s.walls read). `first_group`:
// the group of the first fill's spheres.
void place_fill_spheres(const DemScene& s, BodiesSpec& b, int first_group);

}  // namespace gf
