// Sphere contacts with rigid triangle-mesh walls (triangle_mesh.hpp), beside the analytic walls of
// wall_contact.hpp and with the same laws (laws.hpp) and the same per-species wall constants.
//
// Geometry. Each mesh is rigid, turns at omega about its axis (angle omega t, 0 while motion is off,
// as for the analytic walls) and is carried by its translation (wall_motion.hpp). A grain's centre is carried into the mesh's reference frame, where
// the triangle grid was built once at load: no rebuild, ever. For every listed triangle within the
// grain's radius, the closest point q and its feature (face, edge, vertex) are found.
//
// Which closest points are contacts (no double counting). A contact is a LOCAL MINIMUM of the
// distance from the centre p over the mesh surface, i.e. the direction u = (p - q)/|p - q| lies in
// the normal cone of q's feature (the feature's Voronoi region on the mesh):
//   face    always (a face point is a local minimum of its own plane);
//   edge    for every triangle F sharing the edge, u . m_F >= -1e-9, m_F the unit vector in F's plane
//           normal to the edge pointing away from F: moving from q into F would not bring q nearer.
//           At a convex edge this is the wedge between the two face normals; at a concave edge it is
//           empty (the faces hold the contacts); in a flat region it is the face normal only; at a
//           boundary edge (one triangle) it is the half-space beyond the edge;
//   vertex  for every edge from the vertex to a neighbour w, u . (w - q) <= 1e-9 |w - q|.
// The same local minimum is then found from every triangle sharing its feature (two for an edge, a
// fan for a vertex), and, within rounding, as a face point of one triangle and an edge point of its
// coplanar neighbour. Contacts of one mesh whose closest points coincide (within 1e-6 of the grain's
// radius) are merged into one, keeping a face over an edge over a vertex. So a grain on a flat or
// convex region has one contact wherever it is, and one in a concave corner of k faces has k.
//
// History. A grain keeps up to kMeshSlots contacts with all mesh walls together, in a fixed record
// per row that moves with the row (no map, no allocation). A slot is keyed by the mesh and the flat
// region of the contact's triangle (for an edge or vertex inside one flat region too); an edge or a
// vertex between regions is keyed by itself. A new contact takes the slot of the same key, else the
// unclaimed slot of the same mesh whose normal is within 30 degrees of its own: a grain rolling from
// a triangle to its coplanar neighbour keeps its spring (same region), and one rolling over a convex
// edge onto the next face keeps it too (face -> edge -> face, the normal turning continuously). The
// law turns the spring into the new tangent plane.
//
// Cost. Per grain and mesh: a rotation into the reference frame, a bit test of the grain's grid cell
// (one bit per cell, cache-resident) and, for a cell near the surface, a closest-point test (about
// 30 flops, no square root) for every triangle it lists: those within the largest grain radius
// (plus a law's reach) and 0.87 of a cell edge (the cell edge is that radius) of the cell's centre,
// 3 on average near a 96-segment drum mantle or end disc. A square root and the cone test only for
// the few within the grain's radius; the law only for contacts. Measured on one thread (a shared
// 2-core machine): a settled 2000-grain drum of mantle and two end discs (3 meshes) took 100 ns per
// grain and step in this system, against 10 ns for the vectorised analytic drum of the same scene
// (wall_contact.cpp); the kernel alone on grains spread through the drum, 45 ns. The grid costs a
// 32-bit entry per (cell, triangle near it) plus one per cell, built once at load (the mesh is
// rigid: no rebuild).
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, ContactTable, MeshWalls, Walls (its
//         rotation switch), OverlapLimit.
// Writes: MeshWallForce, MeshWallTorque, MeshContactHistory, MeshWallLoads (each mesh's load, walls.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "engine/system.hpp"
#include "systems/contact/contact_table.hpp"
#include "systems/integrate/force_terms.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/stability/stability_report.hpp"
#include "systems/walls/triangle_mesh.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

struct MeshWall {
  std::string name;
  std::shared_ptr<const TriangleMesh> mesh;  // reference geometry (angle 0), m
  std::shared_ptr<const TriangleGrid> grid;  // over the reference geometry
  Vec3d rot_point{0, 0, 0}, rot_axis{0, 0, 1};
  double omega = 0.0;  // rad/s
  WallMotion motion;   // translation (wall_motion.hpp), after the rotation
};

// The grid's reach: the largest grain radius of the scene plus mesh_wall_reach (m).
MeshWall make_mesh_wall(std::string name, TriangleMesh mesh, double largest_radius);
// How far beyond touching the scene's law acts against a wall (its kReach constant, if it declares
// one; 0 for laws that act in contact only), m.
double mesh_wall_reach(const ContactTable& table);

struct MeshWalls {
  std::vector<MeshWall> list;
};

// Each mesh's load (walls.hpp), written by the mesh contact system.
struct MeshWallLoads : WallLoads {};

struct MeshWallForce {
  ColumnD x, y, z;  // N
  auto columns() { return std::tie(x, y, z); }
};
struct MeshWallTorque {
  ColumnD x, y, z;  // N m
  auto columns() { return std::tie(x, y, z); }
};

// Contacts a grain may have with the mesh walls at once (after merging); a seventh is an error.
inline constexpr std::size_t kMeshSlots = 6;

// One row's contacts: key 0 is an empty slot. n is the contact normal (from the centre towards the
// wall) at the last evaluation; s the law's history (at most 8 doubles, as for analytic walls).
struct alignas(64) MeshSlots {
  std::uint64_t key[kMeshSlots];
  double n[kMeshSlots][3];
  double s[kMeshSlots][8];
};

struct MeshContactHistory {
  Column<MeshSlots> slots;
  auto columns() { return std::tie(slots); }
};

// Attaches the force, torque and history columns to the grains and the walls as a resource.
void attach_mesh_walls(World& world, const MeshWalls& walls);

// Sums every mesh wall's force and torque on each owned row into MeshWallForce/MeshWallTorque, the
// meshes at their angle for time t_contact. Returns whether some overlap passed overlap_limit of the
// grain's diameter. With keep_history false the springs are evaluated but not stored (the priming
// evaluation of a new state, in which no time passes). Instantiated for every law of ContactLaws.
template <class L>
bool compute_mesh_wall_forces(Grains& g, const MeshWalls& walls, bool rotation_enabled, const ContactTable& table,
                              double dt, double t_contact, double overlap_limit = 1.0, bool keep_history = true,
                              std::vector<WallLoad>* loads = nullptr);

// The contacts of one grain as the kernel finds them (for tests): with the meshes at angle omega t.
struct MeshContactPoint {
  std::size_t wall;
  std::uint32_t triangle;
  Feature feature;
  Vec3d q;      // closest point, world frame, m
  Vec3d n;      // unit, from the centre towards q
  double gap;   // |p - q|, m
  std::uint64_t key;
};
std::vector<MeshContactPoint> mesh_contacts_of(const MeshWalls& walls, const Vec3d& p, double radius, double t,
                                               bool rotation_enabled = true);

inline ForceTerm mesh_wall_force_term() { return force_term<MeshWallForce, MeshWallTorque>("mesh_wall_contact"); }

[[noreturn]] void report_mesh_overlap(const Grains& g, const MeshWalls& walls, double limit, const StepContext& step,
                                      double t, bool rotation_enabled);

template <class L>
class MeshWallContact : public SystemBase<MeshWallContact<L>> {
 public:
  using Reads =
      gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, ContactTable, OverlapLimit, MeshWalls, Walls>;
  using Writes = gf::Writes<MeshWallForce, MeshWallTorque, MeshContactHistory, MeshWallLoads>;
  std::string_view name() const override { return "mesh_wall_contact"; }
  void run(World& world, const StepContext& step) override {
    const double t = step.t + (step.prime ? 0.0 : step.dt);
    const double limit = world.resources.get<OverlapLimit>().ratio;
    const MeshWalls& walls = world.resources.get<MeshWalls>();
    const Walls* analytic = world.resources.find<Walls>();
    const bool rotating = analytic == nullptr || analytic->rotation_enabled;
    MeshWallLoads& loads = world.resources.get<MeshWallLoads>();
    if (compute_mesh_wall_forces<L>(world.grains, walls, rotating, world.resources.get<ContactTable>(), step.dt, t,
                                    limit, !step.prime, &loads.now))
      report_mesh_overlap(world.grains, walls, limit, step, t, rotating);
    if (!step.prime) loads.accumulate();
  }
};

}  // namespace gf
