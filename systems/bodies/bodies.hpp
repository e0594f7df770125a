// Composite grains: rigid bodies made of convex dilated polyhedra (../shared/spec/002: a member is a
// convex core ⊕ a sphere of radius r; a body is a rigid union of members, which may overlap and so
// make concave shapes). Two tables, each structure of arrays:
//   Bodies:  one row per rigid body: centre of mass, orientation, velocities, mass and principal
//            inertia, and the force and torque summed over its members' contacts.
//   Members: one row per dilated polyhedron: its body's row, its core's vertices in the body frame,
//            its dilation radius, its bounding sphere, and its centre in the world frame.
// Frames: the body frame has its origin at the centre of mass and its axes along the principal axes
// of inertia, so the inertia tensor is diagonal there (systems/bodies/mass_properties.hpp computes
// both). The orientation q = (w, x, y, z) is the unit quaternion taking body-frame vectors to the
// world frame: a_world = q a_body q*. Velocity, angular velocity, force and torque are world-frame.
// Every row is owned for now: ghost rows (periodic images, other domains) and the re-sorting of rows
// (and with it ids to key contact history by) come with the contacts between members.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "engine/column.hpp"
#include "engine/system.hpp"

namespace gf {

// ---- Bodies' components --------------------------------------------------------------------------

struct BodyPosition {
  ColumnD x, y, z;  // m, centre of mass
  auto columns() { return std::tie(x, y, z); }
};
struct BodyOrientation {
  ColumnD w, x, y, z;  // unit quaternion, body frame -> world frame
  auto columns() { return std::tie(w, x, y, z); }
};
struct BodyVelocity {
  ColumnD x, y, z;  // m/s, of the centre of mass
  auto columns() { return std::tie(x, y, z); }
};
struct BodyAngularVelocity {
  ColumnD x, y, z;  // rad/s, world frame
  auto columns() { return std::tie(x, y, z); }
};
struct BodyMass {
  ColumnD m;      // kg
  ColumnD inv_m;  // 1/kg
  auto columns() { return std::tie(m, inv_m); }
};
struct BodyInertia {
  ColumnD i1, i2, i3;  // kg m^2, principal moments about the body frame's axes 1, 2, 3
  auto columns() { return std::tie(i1, i2, i3); }
};
struct BodyForce {
  ColumnD x, y, z;  // N, world frame, summed over the members' contacts
  auto columns() { return std::tie(x, y, z); }
};
struct BodyTorque {
  ColumnD x, y, z;  // N m, world frame, about the centre of mass
  auto columns() { return std::tie(x, y, z); }
};
// How a body takes part in the run. A fixed body (a hopper's wall or floor, a gate) never moves: the
// integrator leaves it, and its members meet the moving bodies' members as a wall does (the contact
// law's wall parameters, m* the moving body's mass). A removed body (a gate opened, a body that fell
// into a sink) stays in the tables where it was, inert: no contacts, not integrated, not counted.
enum class Motion : std::uint8_t { moving = 0, fixed = 1, removed = 2 };
struct BodyMotion {
  Column<std::uint8_t> state;  // Motion
  auto columns() { return std::tie(state); }
};

// One body's state, for Bodies::push.
struct BodyRow {
  std::array<double, 3> x{};                    // m
  std::array<double, 4> q{1.0, 0.0, 0.0, 0.0};  // (w, x, y, z), normalised on push
  std::array<double, 3> v{}, w{};               // m/s, rad/s (world frame)
  double mass = 0;                              // kg
  std::array<double, 3> inertia{};              // kg m^2, principal moments
  Motion motion = Motion::moving;               // fixed: v and w are set to zero on push
};

struct Bodies {
  static constexpr std::string_view kName = "bodies";
  std::size_t n = 0;  // rows, all owned

  BodyPosition pos;
  BodyOrientation q;
  BodyVelocity vel;
  BodyAngularVelocity omega;
  BodyMass mass;
  BodyInertia inertia;
  BodyForce force;
  BodyTorque torque;
  BodyMotion motion;

  auto components() { return std::tie(pos, q, vel, omega, mass, inertia, force, torque, motion); }
  bool moving(std::size_t i) const { return motion.state[i] == static_cast<std::uint8_t>(Motion::moving); }

  std::size_t owned_rows() const { return n; }
  std::size_t rows() const { return n; }
  // New rows are zero (the orientation too: push sets it).
  void resize(std::size_t rows);
  // Appends a body with zero force and torque; returns its row. Throws std::invalid_argument for a
  // mass or a principal moment that is not positive and finite, or a zero quaternion.
  std::size_t push(const BodyRow& row);
  std::size_t bytes();
};

// ---- Members' components -------------------------------------------------------------------------

struct MemberBody {
  Column<std::uint32_t> row;  // the body's row in Bodies
  auto columns() { return std::tie(row); }
};
// The core's points are CoreVertices' entries [first, first + count); what they mean is its kind's
// (member_core.hpp: a hull's vertices, an ellipsoid's centre and semi-axis ends).
struct MemberCore {
  Column<std::uint32_t> first, count;
  Column<std::uint8_t> kind;  // CoreKind
  auto columns() { return std::tie(first, count, kind); }
};
struct MemberDilation {
  ColumnD r;  // m, the sphere swept over the core
  auto columns() { return std::tie(r); }
};
// A sphere holding the whole dilated member, about its centre in the body frame (the mean of its
// core's vertices: not the smallest such sphere, but cheap and exact to recompute).
struct MemberBound {
  ColumnD cx, cy, cz;  // m, body frame
  ColumnD radius;      // m, max |vertex - centre| + r
  auto columns() { return std::tie(cx, cy, cz, radius); }
};
// The bound's centre in the world frame, refreshed each step from the body's pose (place_members):
// what a broadphase over members reads.
struct MemberCentre {
  ColumnD x, y, z;  // m
  auto columns() { return std::tie(x, y, z); }
};
// All members' core vertices in one flat array (body frame, m); not rows of the Members table.
struct CoreVertices {
  ColumnD x, y, z;
  auto columns() { return std::tie(x, y, z); }
  std::size_t size() const { return x.size(); }
};

// One member, for Members::push: its body's row, its core's kind and points in the body frame, and r.
struct MemberRow {
  std::uint32_t body = 0;
  std::vector<std::array<double, 3>> vertices;  // m, body frame, at least one
  double radius = 0;                            // m, >= 0
  std::uint8_t kind = 0;                        // CoreKind: 0 a hull of the points
};

struct Members {
  static constexpr std::string_view kName = "members";
  std::size_t n = 0;  // rows, all owned

  MemberBody body;
  MemberCore core;
  MemberDilation dilation;
  MemberBound bound;
  MemberCentre centre;
  CoreVertices vertices;

  auto components() { return std::tie(body, core, dilation, bound, centre); }

  std::size_t owned_rows() const { return n; }
  std::size_t rows() const { return n; }
  // Appends a member (its points to CoreVertices, its bound computed); returns its row. The world
  // centre is left zero until place_members. Throws std::invalid_argument for no points, points
  // that are not a core of their kind (a non-finite one, an ellipsoid's slanted axes, ...) or a
  // negative or non-finite radius.
  std::size_t push(const MemberRow& row);
  std::size_t bytes();
};

// Makes body i inert where it stands (Motion::removed; velocities, force and torque zero). Its
// members' contacts end at the next contact evaluation, which drops their springs.
void remove_body(Bodies& bodies, std::size_t i);

// Each member's world centre from its body's pose: c_world = x_body + R(q_body) c_body.
void place_members(Bodies& bodies, Members& members);

// place_members as a system: after the bodies move, before anything reads the members' places.
class PlaceMembers : public SystemBase<PlaceMembers> {
 public:
  using Reads = gf::Reads<BodyPosition, BodyOrientation, MemberBody, MemberBound>;
  using Writes = gf::Writes<MemberCentre>;
  std::string_view name() const override { return "place_members"; }
  void run(World& world, const StepContext& step) override;
};

}  // namespace gf
