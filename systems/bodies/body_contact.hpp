// Contacts of composite grains: every pair of members of different bodies, and every member against
// static plane walls, evaluated with a contact law L (laws.hpp) on the geometry of member_geometry.hpp,
// and summed onto the bodies (../shared/spec/002: the contact of two composites is the set of contacts
// of their member pairs, whose forces and torques add up about each body's centre of mass).
//
// Broadphase. A Verlet list of member pairs whose bounding spheres (MemberBound, placed at
// MemberCentre) are closer than R_a + R_b + skin, found on a CellGrid (cell_grid.hpp) of the members'
// centres with cells of 2 max R + skin, so that every such pair lies in neighbouring cells. Members
// of one body are never paired (they are one rigid piece). The list is rebuilt when some member's
// centre moved more than skin / 2 since the last rebuild: a bounding sphere holds its member whatever
// the body's orientation, so a pair missing from the list is still apart. A body's rotation moves
// the centres of its members off its axis and is counted that way.
//
// History. One entry per member pair touching at the last evaluation (a composite pair touching at
// several members carries one spring per member pair), packed in list order in a PairHistory with
// the law's history layout, seen from the pair's owner: the member of lower id, as the sphere driver
// keeps springs in its owner row's view. Pairs are keyed by the members' ids (pair_key): the ids are
// the Members rows, which are never re-sorted, and the list is kept in key order, so a rebuild
// carries each spring by a merge of the old and new keys. Walls: one record of the law's history
// per (member, plane), zero while apart.
//
// Law inputs. Per member pair the law's constants (computed at each rebuild, from
// L::constants on the two ContactBody records below) and the ContactGeometry of contact_geometry():
// normal from the owner towards the other member, overlap, relative velocity of the contact point and
// relative spin. The law's scalar (double) path is used. Body A (the owner's) gets F and
// arm_a x F + the law's torque_i; body B gets -F and arm_b x (-F) + torque_j: each force acts at the
// contact point and the law's own torques (rolling resistance) act about it, so the pair conserves
// linear and angular momentum exactly where the law's torques are a couple (torque_j = -torque_i).
//
// A member as the law's ContactBody (one record per member, shared by all its contacts):
//   mass    its body's mass m. Normal and tangential damping use m* = m_A m_B / (m_A + m_B) (against
//           a wall, m_A), as for spheres: the translational response of two free bodies. It ignores
//           the rotational inertia that a contact off the line of centres also moves, so an
//           eccentric contact is damped somewhat more than its nominal restitution says.
//   inertia its body's smallest principal moment, for rotational terms (the linear law's rolling
//           damping and period): the fastest rotational response over the body's axes, so the
//           critical period is a lower bound and the rolling damping ratio is the intended one about
//           that axis and lower (never overdamped) about the others.
//   radius  the member's dilation radius r, for laws that need a radius (Hertz's R*, the rolling
//           torque's lever mu_r R). Around a vertex of its core a dilated member's surface is a
//           sphere of radius r, along an edge a cylinder of radius r, on a face flat: r is the
//           smallest local radius of curvature the member has anywhere. So R* = r_A r_B / (r_A + r_B)
//           is exact for vertex-to-vertex contacts and a lower bound elsewhere (the softer side of
//           Hertz, whose theory has no finite radius on a face). A member with r = 0 (a sharp core)
//           has no Hertz stiffness: give such bodies rounded members.
//
// Fixed and removed bodies (BodyMotion): pairs of members of two fixed bodies are never listed, and
// a removed body's members are in no pair and touch no plane. A moving member against a fixed one is
// the law's particle against a wall (the [contact.wall] parameters, m* = the moving body's mass); it
// is listed as the pair's owner whatever the ids' order.
//
// Reads:  the bodies' pose, velocities, mass, inertia and motion; the members' rows, cores and centres;
//         BodyPlanes, BodyContactModel<L>.
// Writes: BodyForce, BodyTorque (set: the sum of every member contact), BodyContactState.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "engine/system.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact_split.hpp"
#include "systems/broadphase/cell_grid.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/contact_law.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// A wall the bodies meet: a plane through `point` whose unit `normal` points out of the wall, to the
// side the bodies are on (as member_plane takes it, and as a scene's plane walls state theirs); or,
// with `cylinder`, the inside of a cylinder of `radius` about the axis through `point` along the
// unit `normal` (member_cylinder). It may turn at `omega` (rad/s) about the axis through `rot_point`
// along `rot_axis` (a drum's mantle, its end plates: its surface stays in place), and translate by
// `motion` (wall_motion.hpp: a velocity, a vibration or a velocity table), which carries the surface
// and the rotation point with it. The contact feels the surface's velocity there.
struct BodyPlane {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d normal = Eigen::Vector3d::UnitY();
  bool cylinder = false;
  double radius = 0;  // m
  double omega = 0;   // rad/s
  Eigen::Vector3d rot_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d rot_axis = Eigen::Vector3d::UnitZ();
  WallMotion motion{};
  // At the last placement (place_body_planes): the translation's offset d(t) and velocity (zero
  // while the walls stand still, and until placed).
  Eigen::Vector3d offset = Eigen::Vector3d::Zero(), velocity = Eigen::Vector3d::Zero();
};
struct BodyPlanes {
  std::vector<BodyPlane> list;
};

// Places every plane for time t: offset d(t) and velocity d'(t - lag) (the contacts see the bodies'
// velocities of the half-step, as walls.hpp says for grains); with moving = false, both zero (the
// walls stand still while a fill settles).
void place_body_planes(BodyPlanes& planes, double t, double lag, bool moving);

// The law's parameters: one material for every body (bodies have no species yet), the parameters of
// every member pair of different bodies, and those against the planes (a law's wall parameters, e.g.
// Hertz-Mindlin's wall material).
template <class L>
struct BodyContactModel {
  typename L::Material material{};
  typename L::Params pair{};
  typename L::Params wall{};
};

// The member-pair Verlet list, in increasing key order, with the law's constants per pair.
struct MemberPairList {
  std::vector<std::uint32_t> a, b;     // member rows (= ids) of different bodies: a < b, except that a
                                       // moving member paired with a fixed one is a (the owner)
  std::vector<std::uint64_t> key;      // pair_key(a, b), increasing
  std::size_t width = 0;               // the law's constants per pair
  std::vector<double> constants;       // width per pair
  std::vector<double> wall_constants;  // width per member
  std::size_t pairs() const { return key.size(); }
};

// Per (member, plane) history of the law, `width` doubles each, zero while apart; and the last
// evaluation's load of each touching pair on the member: its force and its moment about the plane's
// rotation point (read only where touching; not checkpointed, as every evaluation sets it).
struct MemberWallHistory {
  static constexpr std::size_t kLoad = 6;
  std::size_t members = 0, planes = 0, width = 0;
  std::vector<double> value;           // ((member * planes) + plane) * width + q
  std::vector<std::uint8_t> touching;  // member * planes + plane: in contact at the last evaluation
  std::vector<double> load;            // ((member * planes) + plane) * kLoad + q: fx fy fz mx my mz
  double* at(std::size_t m, std::size_t p) { return value.data() + (m * planes + p) * width; }
  double* load_at(std::size_t m, std::size_t p) { return load.data() + (m * planes + p) * kLoad; }
};

// What one evaluation found.
struct BodyContactReport {
  std::size_t pair_contacts = 0;  // member pairs touching
  std::size_t fixed_contacts = 0;  // of them, a moving member touching a fixed body's member
  std::size_t wall_contacts = 0;  // (member, plane) pairs touching
  double max_overlap = 0;         // m, the largest overlap of any contact
  bool rebuilt = false;           // the member-pair list was rebuilt first
};

// Where the last evaluation's largest overlap is, for the stop's message: the two members and their
// bodies (rows), the second -1 for a member against a wall; the first body's centre (m). Not part
// of the report (which checkpoints hold as it is): recomputed by every evaluation.
struct OverlapSite {
  std::int64_t member[2] = {-1, -1}, body[2] = {-1, -1};
  double centre[3] = {0, 0, 0};
};

// Everything the contacts of bodies keep from step to step.
struct BodyContactState {
  double skin = 0;            // m, the Verlet skin of the member-pair list
  bool valid = false;         // false: rebuild (and recompute the law's constants) at the next evaluation
  std::int64_t rebuilds = 0;
  CellGrid grid;
  std::vector<double> ref_x, ref_y, ref_z;  // members' centres at the last rebuild
  MemberPairList list;
  PairHistory history;        // member pairs touching at the last evaluation (list order)
  MemberWallHistory walls;
  // Each plane's load (walls.hpp): the last evaluation's, and the sums over the full steps, which
  // walls.csv reports and the checkpoints keep.
  WallLoads loads;
  // Per member, its body's Motion at the last evaluation: a change rebuilds the list, so a removed
  // body's springs are dropped and a fixed body's pairs take the wall's constants.
  std::vector<std::uint8_t> motion;
  BodyContactReport last;     // the last evaluation's counts, for the outputs
  OverlapSite worst;          // where last.max_overlap is
  // m: an overlap beyond it stops the run (BodyContact throws StabilityError); a scene sets it to
  // run.max_overlap times its thinnest moving shape's smallest outer dimension.
  double overlap_limit = std::numeric_limits<double>::infinity();
};

// Throws StabilityError naming the step and the limit when the last evaluation's largest overlap
// passed state.overlap_limit.
void check_body_overlap(const BodyContactState& state, const StepContext& step);

// True when the list must be rebuilt: none yet, the member count changed, or some member's centre
// moved more than skin / 2 since the last rebuild.
bool member_pairs_stale(const Members& members, const BodyContactState& state);
// Rebuilds the list's pairs and keys from the members' centres (MemberCentre, placed), carries each
// touching pair's history to its new place and drops the others'. The law's constants are left to
// the caller (compute_body_contacts refreshes them).
void rebuild_member_pairs(const Members& members, BodyContactState& state);

// Rebuilds the list when stale, then evaluates every member pair and (member, plane) contact with law
// L and sets each body's force and torque to their sums. Members must have been placed
// (place_members) at the bodies' current pose. dt is the step (the springs' increment). Instantiated
// for every law of ContactLaws. Throws std::invalid_argument for a skin that is not positive, a
// member naming no body, or law constants that are not finite. The planes stand at their last
// placement (place_body_planes), and state.loads.now receives each plane's load.
// With turning = false the walls do not turn (a drum while its fill settles). With a split of more
// than one process (body_contact_split.hpp) this process evaluates its share and the outcomes are
// shared; every process must then make the call with the same state (collective).
template <class L>
BodyContactReport compute_body_contacts(Bodies& bodies, const Members& members, const BodyPlanes& planes,
                                        const BodyContactModel<L>& model, BodyContactState& state, double dt,
                                        bool turning = true, const BodyContactSplit* split = nullptr);

// compute_body_contacts as a system: after the members are placed, before the bodies' closing kick.
template <class L>
class BodyContact : public SystemBase<BodyContact<L>> {
 public:
  using Reads = gf::Reads<BodyPosition, BodyOrientation, BodyVelocity, BodyAngularVelocity, BodyMass, BodyInertia,
                          BodyMotion, MemberBody, MemberCore, MemberDilation, MemberBound, MemberCentre, CoreVertices,
                          BodyContactModel<L>, Walls, BodyContactSplit>;
  using Writes = gf::Writes<BodyForce, BodyTorque, BodyContactState, BodyPlanes>;  // BodyPlanes: their placement
  std::string_view name() const override { return "body_contact"; }
  // The walls turn unless the scene's walls have their rotation off (while a fill settles).
  static bool turning(World& world) {
    const Walls* w = world.resources.find<Walls>();
    return !w || w->rotation_enabled;
  }
  void run(World& world, const StepContext& step) override {
    BodyContactState& state = world.resources.get<BodyContactState>();
    BodyPlanes& planes = world.resources.get<BodyPlanes>();
    // The bodies' positions were advanced by the first half of the step: they refer to t + dt.
    place_body_planes(planes, step.t + (step.prime ? 0.0 : step.dt), 0.5 * step.dt, turning(world));
    compute_body_contacts<L>(world.tables.get<Bodies>(), world.tables.get<Members>(), planes,
                             world.resources.get<BodyContactModel<L>>(), state, step.dt, turning(world),
                             world.resources.find<BodyContactSplit>());
    if (!step.prime) state.loads.accumulate();
    if (state.last.max_overlap > state.overlap_limit) check_body_overlap(state, step);
  }
};

}  // namespace gf
