// The seam between the geometry stage and the law stage of the contact pipeline, and what every
// contact law declares. A law is one header: a struct with
//   name, title                 its scene name (`[contact] model = ...`) and a line for `grainflow check`
//   Material                    what a species states for it (read_material, from a [[species]] table)
//   Params, read_params         what a scene states per species pair and against walls, read through
//   fields (wall_fields)        its key table (engine/field_table.hpp), from which the manual's
//                               reference is generated; wall_fields where [contact.wall] differs
//   kConstants, constants()     the per type-pair constants a kernel reads (computed once, at load)
//   history                     the per-contact history component: its name and the names of its
//                               doubles (at most kMaxHistory); the broadphase and the checkpoint carry
//                               it without knowing what it is
//   critical_terms()            the time-step terms (s) of one pair of bodies, each with its name
//   evaluate()                  the force, written once for double and for xsimd batches
//   kReach (optional)           for a law that acts before touching: its constant holding the reach
// Drivers (pair_contact, wall_contact) are templates on the law; laws.hpp registers them.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

// Per type-pair constants a law may declare.
inline constexpr std::size_t kMaxConstants = 8;

// The geometry stage's output for one contact (or a batch), seen from row i:
//   n     unit normal from i's centre towards the contact (towards j, or the wall)
//   delta overlap, m (> 0 in contact)
//   v     velocity of i's contact point relative to the other body's, m/s
//   w     angular velocity of i relative to the other body, rad/s
template <class T>
struct ContactGeometry {
  V3<T> n;
  T delta;
  V3<T> v;
  V3<T> w;
};

// The law stage's output: force on i (normal + tangential; the other body gets minus it), its
// tangential part (the driver turns it into torques with the lever arms it knows), and the torques
// the law applies besides (rolling resistance) on i and on the other body.
template <class T>
struct ContactForce {
  V3<T> force;
  V3<T> force_t;
  V3<T> torque_i;
  V3<T> torque_j;
};

// One body of a contact as the constants see it: a species, or a wall (infinite mass, rigid
// unless the law's wall parameters say otherwise).
template <class Material>
struct ContactBody {
  double mass = 0;     // kg (0 for a wall)
  double inertia = 0;  // kg m^2
  double radius = 0;   // m
  Material material{};
  bool wall = false;
  // m/s^2: the magnitude of the scene's gravity, filled in by the scene for laws whose forces are
  // multiples of a weight (representative_volume.hpp); 0 where no scene states one (and for walls).
  double gravity = 0;
};

// A law whose force acts before touching declares kReach, the index of its per type-pair constant
// that holds the reach (m): a pair within r_i + r_j + reach (a wall within r_i + reach) interacts,
// with a negative overlap. The drivers test it with `if constexpr`, so the laws that act only in
// contact compile to the code they had; the neighbour search looks the largest reach further
// (ContactTable::reach).
template <class L>
concept ReachingLaw = requires {
  { L::kReach } -> std::convertible_to<std::size_t>;
};

// A time-step term of a law: a time (s) that dt must stay a `dt_safety` fraction of, and its name.
struct StepTerm {
  double time;
  std::string term;
};

// A history component: per contact, named doubles seen from row i. `odd`: they change sign when
// the pair's rows trade places (springs and angles do), which the broadphase applies when a rebuild
// makes the other row the owner.
struct HistoryLayout {
  std::string_view component;
  std::vector<std::string_view> fields;
  bool odd = true;
};

// Gives a law's history table its component, fields and width (no entries yet).
inline void set_layout(PairHistory& h, const HistoryLayout& layout) {
  h.component = std::string(layout.component);
  h.fields.assign(layout.fields.begin(), layout.fields.end());
  h.exchange_sign = layout.odd ? -1.0 : 1.0;
  h.width = layout.fields.size();
  h.resize(0);
}

}  // namespace gf
