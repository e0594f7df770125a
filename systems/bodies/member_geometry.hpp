// Contact geometry of the members of composite grains (dilated convex polyhedra: a convex core ⊕ a
// sphere of radius r, ../shared/spec/002). Two members touch where the distance between their cores
// is below r_A + r_B; the stage turns a pair into what the contact laws consume (contact_law.hpp):
// the unit normal n from A to B, the overlap delta = r_A + r_B - (distance between the cores), the
// contact point, and the lever arms from each body's centre of mass to it (vectors: a body's centre
// is not on the normal line, unlike a sphere's).
//
// Method (libccd, convex collision detection through support functions):
//   - Cores apart: GJK distance with closest points. libccd 2.1 has no distance query (its GJK only
//     answers "do they intersect"; ccdGJKDist2 is FCL's extension, not libccd's), so the GJK
//     iteration is written here (van den Bergen 1999, with Ericson 2005's closest points of a
//     segment, triangle and tetrahedron to the origin as the sub-simplex step), calling libccd's
//     support interface: the ccd_t's support1/support2 and center1/center2 callbacks, its
//     dist_tolerance and max_iterations. The cores' closest points are the barycentric combinations
//     of the final simplex's support points; for polytopes GJK ends on the closest features
//     themselves, so they are exact to round-off.
//   - Cores interpenetrating (delta above r_A + r_B, a deep contact; with small r the usual case for
//     sharp grains): libccd's ccdMPRPenetration (Minkowski Portal Refinement) gives the direction in
//     which the ray from the cores' centres leaves A - B. MPR's own depth is the distance to its last
//     portal triangle, which depends on the path the portal took: swapping A and B or turning the
//     pair changed it by up to 54 um on millimetre grains in the tests. So MPR's direction is refined
//     by a descent that uses GJK from outside: a point a margin beyond A - B along the direction has
//     a closest point c on it, the outward normal there becomes the new direction, and the depth
//     along it (c . n) never grows. It ends on a face of A - B that holds the origin's foot, a local
//     minimum of the penetration depth, with p_A - p_B = depth n; delta = depth + r_A + r_B along
//     that normal. For cores that met moving along their line of centres this is the face they met
//     through, so the normal does not jump as they touch (tested), even where another face is a
//     little shallower; in random deep overlaps it is the minimum depth in about 4 cases of 5. Not
//     libccd's EPA (ccdGJKPenetration): it fails on stacked boxes (a NaN direction, reported upstream),
//     the face-to-face contact resting grains make.
//   - Cores touching within the tolerance: the same descent, from MPR's direction or, when MPR sees
//     no depth, from the bounding centres' direction; the depth it gives may be slightly negative.
// All of it runs in a frame scaled by the pair's size (the sum of the bounding radii), about the
// midpoint of the bounding centres: libccd's zero tests are absolute (DBL_EPSILON), and tolerances
// are then relative to the grains (kMemberTolerance of their size), as right for 1 mm as for 1 m.
//
// Spheres are members with a point core. A plane wall meets a member with the overlap of its lowest
// point (the core's support point along -normal, the normal pointing out of the wall). A hull is
// pushed at the mean of the vertices whose dilation spheres reach through the plane, each weighted
// by its own overlap (a smooth core, at its lowest point): a box resting flat on a floor is pushed at its face's centre, and a small tilt moves the
// point towards the lower side (a restoring torque that grows with the tilt, instead of the lowest
// corner's, which changes sides with the round-off). Apart, the vertices tied within the tolerance
// are averaged.
// A face-to-face contact between members gets one point of the touching patch, whichever GJK's
// simplex ends on; the laws see one contact per member pair.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/member_core.hpp"
#include "systems/contact/contact_law.hpp"

namespace gf {

// GJK's stopping gap and the MPR portal tolerance, relative to the pair's size. 1e-12 lies more
// than three orders above double round-off (2.2e-16) at that size, so the iterations stop on a
// converged feature rather than on noise, and distances come out within 1e-12 of the size.
inline constexpr double kMemberTolerance = 1e-12;
// Iteration caps for GJK, MPR and the penetration's descent: polytopes with a few dozen vertices
// converge in well under 30.
inline constexpr unsigned long kMemberMaxIterations = 100;

// A member as the geometry reads it: its core's kind and points in a frame of its own (three spans
// of equal length, structure of arrays like the Members table's CoreVertices; member_core.hpp), that
// frame's pose in the world, r, its body's centre of mass and a bounding sphere. Built by the
// functions below.
struct MemberShape {
  CoreKind kind = CoreKind::hull;
  std::span<const double> x, y, z;                             // m, the core's points, own frame
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();      // own frame -> world
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();            // m, world: the own frame's origin
  double radius = 0;                                           // m, dilation r
  Eigen::Vector3d centre_of_mass = Eigen::Vector3d::Zero();    // m, world: the lever arms start here
  Eigen::Vector3d bound_centre = Eigen::Vector3d::Zero();      // m, world
  double bound_radius = 0;                                     // m, holds the whole dilated member

  std::size_t vertices() const { return x.size(); }
  Eigen::Vector3d vertex(std::size_t i) const;  // m, world: the core's point i
  CoreView core() const { return {kind, x, y, z}; }
  // m, world: the core's point farthest along the world direction d.
  Eigen::Vector3d support(const Eigen::Vector3d& d) const;
};

// Member row `m` of the tables at its body's current pose (body frame = own frame, its origin the
// centre of mass). Reads the body's position and orientation, not MemberCentre.
MemberShape member_shape(const Bodies& bodies, const Members& members, std::size_t m);
// A core given in a body frame at pose (origin = the body's centre of mass, rotation body -> world).
// The bound is the core's (core_centre and core_reach, plus r). The shape views `core`'s arrays, so
// `core` must outlive it (likewise the tables for member_shape). Throws std::invalid_argument for
// points that are not a core of their kind (check_core).
MemberShape posed_member(const CorePoints& core, double radius, const Eigen::Vector3d& origin,
                         const Eigen::Matrix3d& rotation);
// A core given by world-frame vertices, of a body whose centre of mass is `centre_of_mass`.
MemberShape world_member(const CorePoints& core, double radius, const Eigen::Vector3d& centre_of_mass);

// How far the pair got:
//   apart        the bounding spheres do not overlap; only delta is set: minus the gap between the
//                spheres, an upper bound on the true overlap (so below zero)
//   separated    the cores are apart (GJK), or touch within the tolerance: every field exact,
//                delta > 0 when the members touch
//   penetrating  the cores interpenetrate (MPR and the descent; a wall: the core crosses the
//                plane): delta > r_A + r_B
enum class MemberProximity : std::uint8_t { apart, separated, penetrating };

// One member pair's contact, seen from A (for a wall: B is the wall).
struct MemberContact {
  MemberProximity kind = MemberProximity::apart;
  Eigen::Vector3d n = Eigen::Vector3d::Zero();      // unit normal from A towards B
  double delta = 0;                                  // m, overlap: r_A + r_B - core distance
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  // m, world: midway between the two surfaces along n
  Eigen::Vector3d arm_a = Eigen::Vector3d::Zero();  // m, point - A's centre of mass
  Eigen::Vector3d arm_b = Eigen::Vector3d::Zero();  // m, point - B's centre of mass (zero for a wall)
  double core_distance = 0;                          // m, between the cores (minus the depth if penetrating)

  bool touching() const { return kind != MemberProximity::apart && delta > 0; }
};

// Two members. The contact point lies at (p_A + p_B)/2 + (r_A - r_B)/2 n, p_A and p_B the cores'
// closest points (for penetrating cores, their points deepest in each other along n).
MemberContact member_member(const MemberShape& a, const MemberShape& b);
// A member and a sphere (a point core at `centre` with radius `radius`, its own centre of mass).
MemberContact member_sphere(const MemberShape& a, const Eigen::Vector3d& centre, double radius);
// A member and a plane wall through `point` whose unit normal `normal` points out of the wall, to
// the side the grains are on. n = -normal; delta = r - h, h the height of the core's lowest point
// above the plane; the point is midway between the member's surface and the plane.
MemberContact member_plane(const MemberShape& a, const Eigen::Vector3d& point, const Eigen::Vector3d& normal);
// A member inside a cylinder wall (a drum's mantle) of `radius` about the axis through `point` along
// the unit `axis`. Each core vertex at distance rho from the axis reaches rho + r - radius through
// the wall; delta is the largest such depth (exact: a convex core is farthest from an axis at a
// vertex). n is the outward radial direction averaged over the vertices through the wall, weighted
// by their depth, and the point their depth-weighted mean, each midway between the member's surface
// and the wall along its own radial direction: a face resting across the curved wall, touching it
// along two edges, is pushed at its middle, as member_plane pushes a face lying on a floor. A smooth
// core's point farthest from the axis is found by ascent on its support points (each step's radial
// direction at the last point gives the next point, which is no nearer the axis), exact to 1e-12 of
// the member's size where the wall's radius is larger than the member, as a drum's is; the force acts
// there.
MemberContact member_cylinder(const MemberShape& a, const Eigen::Vector3d& point, const Eigen::Vector3d& axis,
                              double radius);

// The contact as a law consumes it, from the bodies' velocities and angular velocities (world): the
// relative velocity of A's contact point, v = (v_A + w_A × arm_a) - (v_B + w_B × arm_b), and the
// relative spin w_A - w_B. For a wall, v_B is the wall's velocity at the contact point.
ContactGeometry<double> contact_geometry(const MemberContact& c, const Eigen::Vector3d& v_a, const Eigen::Vector3d& w_a,
                                         const Eigen::Vector3d& v_b, const Eigen::Vector3d& w_b);

}  // namespace gf
