#include "systems/walls/mesh_wall_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "engine/run_loop.hpp"
#include "engine/scene.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/sphere_geometry.hpp"
#include "systems/walls/wall_row_blocks.hpp"

namespace gf {

namespace {

// A mesh's placement at one time: a rotation by a fixed angle about a unit axis through a point
// (Rodrigues), its cosine and sine computed once per evaluation, not per grain, after which the
// mesh is carried by its offset d (wall_motion.hpp); with the surface's translational velocity v
// and angular velocity (spin) at that time.
struct Turn {
  Vec3d k{0, 0, 1}, o{0, 0, 0}, d{0, 0, 0}, v{0, 0, 0}, spin{0, 0, 0};
  double c = 1.0, s = 0.0;
  bool identity = true;
  Turn() = default;
  // The placement of `w` at time t (none while motion is off), its velocity at t - lag (walls.hpp).
  Turn(const MeshWall& w, double t, bool enabled, double lag = 0.0) : k(w.rot_axis), o(w.rot_point) {
    const double angle = enabled ? w.omega * t : 0.0;
    c = std::cos(angle), s = std::sin(angle);
    if (enabled && w.motion.moves()) d = w.motion.offset(t), v = w.motion.rate(t - lag);
    spin = (enabled ? w.omega : 0.0) * w.rot_axis;
    identity = angle == 0.0 && d.x == 0.0 && d.y == 0.0 && d.z == 0.0;
  }
  // The vector turned by +angle (sign 1) or -angle (sign -1).
  Vec3d vec(const Vec3d& v_in, double sign) const {
    if (c == 1.0 && s == 0.0) return v_in;
    const Vec3d kxv = cross(k, v_in);
    const double kv = dot(k, v_in);
    return (c * v_in + (sign * s) * kxv) + (kv * (1.0 - c)) * k;
  }
  Vec3d origin() const { return o + d; }  // the rotation point, carried
  Vec3d to_reference(const Vec3d& p) const { return identity ? p : o + vec(p - d - o, -1.0); }
  bool same_as(const Turn& t) const {
    return identity == t.identity && c == t.c && s == t.s && k.x == t.k.x && k.y == t.k.y && k.z == t.k.z &&
           o.x == t.o.x && o.y == t.o.y && o.z == t.o.z && d.x == t.d.x && d.y == t.d.y && d.z == t.d.z;
  }
  Vec3d to_world(const Vec3d& p) const { return identity ? p : o + d + vec(p - o, 1.0); }
};

constexpr double kConeTol = 1e-9;   // of a unit direction: the cone tests' allowance for rounding
constexpr double kMergeTol = 1e-6;  // of the grain's radius: closest points closer are one contact

// Whether direction u (from q to the centre, unit, reference frame) lies in the normal cone of q's
// feature on the mesh: q is then a local minimum of the distance to the centre (see the header).
bool in_normal_cone(const TriangleMesh& m, std::uint32_t t, Feature f, const Vec3d& u, const Vec3d& q) {
  if (f == Feature::Face) return true;
  const auto k = static_cast<std::size_t>(feature_index(f));
  if (is_edge(f)) {
    const std::uint32_t e = m.edge_of[t][k];
    for (std::uint32_t a = m.edge_start[e]; a < m.edge_start[e + 1]; ++a) {
      const std::uint32_t j = m.edge_tri[a];
      for (std::size_t kk = 0; kk < 3; ++kk)
        if (m.edge_of[j][kk] == e && dot(u, m.edge_out[j][kk]) < -kConeTol) return false;
    }
    return true;
  }
  const std::uint32_t v = m.tri[t][k];
  for (std::uint32_t a = m.vertex_start[v]; a < m.vertex_start[v + 1]; ++a) {
    const Vec3d w = m.vertex[m.vertex_nbr[a]] - q;
    if (dot(u, w) > kConeTol * std::sqrt(dot(w, w))) return false;
  }
  return true;
}

int rank(Feature f) { return f == Feature::Face ? 0 : (is_edge(f) ? 1 : 2); }

// Slot key: the mesh (bits 40 and up, from 1) and the flat region of the triangle, or for an edge
// or vertex contact whose direction is not its triangle's normal, the edge (kind 1) or vertex
// (kind 2) itself (bits 38-39).
std::uint64_t key_of(const TriangleMesh& m, std::size_t wall, std::uint32_t t, Feature f, const Vec3d& u) {
  const std::uint64_t base = static_cast<std::uint64_t>(wall + 1) << 40;
  if (f == Feature::Face || std::abs(dot(u, m.normal[t])) >= 1.0 - kConeTol) return base | m.region[t];
  const auto k = static_cast<std::size_t>(feature_index(f));
  if (is_edge(f)) return base | (std::uint64_t{1} << 38) | m.edge_of[t][k];
  return base | (std::uint64_t{2} << 38) | m.tri[t][k];
}

struct Hit {
  std::uint32_t wall, tri;
  Feature f;
  Vec3d q, u;  // reference frame
  double d;
};

// The merged contacts of a sphere (centre p, radius r, world frame; r includes a law's reach) with
// every mesh; `turn` holds each mesh's rotation. Returns their number; more than kMeshSlots is an error.
std::size_t find_hits(const MeshWalls& walls, const Turn* turn, const Vec3d& p, double r, Hit* hits) {
  std::size_t nh = 0;
  const double r2 = r * r, merge2 = (kMergeTol * r) * (kMergeTol * r);
  Vec3d pr = p;
  for (std::size_t w = 0; w < walls.list.size(); ++w) {
    const MeshWall& mw = walls.list[w];
    const TriangleMesh& m = *mw.mesh;
    // Meshes that turn together (a mixer's housing, rings and blades) share one reference position
    // (mesh_wall_contact_bench, 1 thread, five alternated rounds: 143-148 us shared, 155-161 us not).
    if (w == 0 || !turn[w].same_as(turn[w - 1])) pr = turn[w].to_reference(p);
    const std::size_t first = nh;
    for (const std::uint32_t t : mw.grid->near(pr)) {
      // The triangle is no nearer than its plane, nor than its bounding sphere: most listed triangles
      // (the neighbours of the facet a grain rests on, the far triangles of a flat ring) fail one of
      // these cheap tests, which reject nothing the full test would keep.
      const double dn = dot(pr - m.corner(t, 0), m.normal[t]);
      if (dn * dn >= r2) continue;
      const Vec3d ec = pr - m.centre[t];
      if (dot(ec, ec) >= (m.bound[t] + r) * (m.bound[t] + r)) continue;
      const ClosestPoint cp = closest_point_on_triangle(pr, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2));
      const Vec3d dv = pr - cp.q;
      const double d2 = dot(dv, dv);
      if (d2 >= r2) continue;
      const double d = std::sqrt(d2);
      const Vec3d u = d > 0.0 ? (1.0 / d) * dv : m.normal[t];
      if (!in_normal_cone(m, t, cp.feature, u, cp.q)) continue;
      bool merged = false;
      for (std::size_t h = first; h < nh; ++h) {
        const Vec3d e = hits[h].q - cp.q;
        if (dot(e, e) > merge2) continue;
        merged = true;
        if (rank(cp.feature) < rank(hits[h].f)) hits[h] = {static_cast<std::uint32_t>(w), t, cp.feature, cp.q, u, d};
        break;
      }
      if (merged) continue;
      if (nh == kMeshSlots)
        throw StabilityError("a grain at (" + short_number(p.x) + ", " + short_number(p.y) + ", " + short_number(p.z) +
                             ") m touches more than " + std::to_string(kMeshSlots) +
                             " separate features of the mesh walls at once (mesh '" + mw.name +
                             "'). Fix: the mesh has a hole, a slot or folds narrower than a grain (a grain in a "
                             "polygonal hole touches every side of it), or overlapping copies of a surface: widen "
                             "or close the hole, remove the copies, or remesh with coarser triangles there");
      hits[nh++] = {static_cast<std::uint32_t>(w), t, cp.feature, cp.q, u, d};
    }
  }
  return nh;
}

template <class Law>
bool mesh_forces(Grains& g, const MeshWalls& walls, bool rotation_enabled, const ContactTable& table, double dt,
                 double t_contact, double overlap_limit, bool keep_history, std::vector<WallLoad>* loads) {
  constexpr std::size_t K = Law::kConstants, H = Law::kHistory;
  static_assert(H <= 8, "a wall contact's history fits a slot");
  const std::size_t nw = walls.list.size();
  std::vector<Turn> turn(nw);
  for (std::size_t w = 0; w < nw; ++w) turn[w] = Turn(walls.list[w], t_contact, rotation_enabled, 0.5 * dt);
  MeshWallForce& force = g.extras.get<MeshWallForce>();
  MeshWallTorque& torque = g.extras.get<MeshWallTorque>();
  Column<MeshSlots>& hist = g.extras.get<MeshContactHistory>().slots;
  const double lim2 = 2.0 * overlap_limit;
  std::vector<double> sums;
  const bool over = for_wall_row_blocks(g.n_owned, 256, nw, sums, [&](std::size_t r0, std::size_t r1, double* load,
                                                                     double& worst) {
    Hit hits[kMeshSlots];
    for (std::size_t i = r0; i != r1; ++i) {
      const Vec3d p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
      const double ri = g.radius.r[i];
      const double* kc = table.wall(static_cast<std::size_t>(g.species.type[i]));
      // A law that acts before touching (one declaring kReach) reaches the wall from r + reach.
      double reach = 0.0;
      if constexpr (ReachingLaw<Law>) reach = kc[static_cast<std::size_t>(Law::kReach)];
      const std::size_t nh = find_hits(walls, turn.data(), p, ri + reach, hits);
      MeshSlots& old = hist[i];
      Vec3d f{0, 0, 0}, tq{0, 0, 0};
      if (nh == 0) {
        if (old.key[0] != 0 && keep_history) std::fill(std::begin(old.key), std::end(old.key), std::uint64_t{0});
      } else {
        const Vec3d vi{g.vel.x[i], g.vel.y[i], g.vel.z[i]};
        const Vec3d wi = g.spin ? Vec3d{g.omega.x[i], g.omega.y[i], g.omega.z[i]} : Vec3d{0.0, 0.0, 0.0};
        std::array<double, K> c;
        std::copy(kc, kc + K, c.begin());
        if constexpr (SizedLaw<Law>)
          if (table.sized()) {  // grains of a size distribution (size_scaling.hpp)
            const auto a = static_cast<std::size_t>(g.species.type[i]);
            Law::resize(c, wall_size_ratio(g.mass.m[i], ri, table.nominal_mass()[a], table.nominal_radius()[a]));
          }
        MeshSlots now{};
        int from[kMeshSlots];
        bool claimed[kMeshSlots] = {};
        Vec3d nrm[kMeshSlots];
        for (std::size_t h = 0; h < nh; ++h) {
          const Hit& x = hits[h];
          const MeshWall& mw = walls.list[x.wall];
          now.key[h] = key_of(*mw.mesh, x.wall, x.tri, x.f, x.u);
          nrm[h] = -turn[x.wall].vec(x.u, 1.0);
          from[h] = -1;
          for (std::size_t j = 0; j < kMeshSlots && old.key[j] != 0; ++j)
            if (!claimed[j] && old.key[j] == now.key[h]) {
              from[h] = static_cast<int>(j);
              claimed[j] = true;
              break;
            }
        }
        // Unmatched contacts take the unclaimed slot of their mesh with the nearest normal (within 30 degrees).
        for (std::size_t h = 0; h < nh; ++h) {
          if (from[h] >= 0) continue;
          double best = std::cos(std::numbers::pi / 6.0);
          for (std::size_t j = 0; j < kMeshSlots && old.key[j] != 0; ++j) {
            if (claimed[j] || (old.key[j] >> 40) != (now.key[h] >> 40)) continue;
            const double cs = nrm[h].x * old.n[j][0] + nrm[h].y * old.n[j][1] + nrm[h].z * old.n[j][2];
            if (cs >= best) best = cs, from[h] = static_cast<int>(j);
          }
          if (from[h] >= 0) claimed[from[h]] = true;
        }
        for (std::size_t h = 0; h < nh; ++h) {
          const Hit& x = hits[h];
          const Vec3d n = nrm[h];
          const Turn& tr = turn[x.wall];
          // The mesh's translation enters as the grain's velocity relative to it. A law acting before
          // touching takes the wall's closest point as the contact point (sphere_geometry.hpp).
          SphereContact<double> sc;
          if constexpr (ReachingLaw<Law>)
            sc = sphere_wall_surface(p, n, x.d, ri, vi - tr.v, wi, tr.spin, tr.origin());
          else
            sc = sphere_wall(p, n, x.d, ri, vi - tr.v, wi, tr.spin, tr.origin());
          worst = std::max(worst, (ri - x.d) - lim2 * ri);
          std::array<double, H> s{};
          if (from[h] >= 0) std::copy(old.s[from[h]], old.s[from[h]] + H, s.begin());
          const ContactForce<double> res = Law::evaluate(true, sc.g, c, dt, s);
          std::copy(s.begin(), s.end(), now.s[h]);
          now.n[h][0] = n.x, now.n[h][1] = n.y, now.n[h][2] = n.z;
          const Vec3d tw = sc.li * cross(n, res.force_t) + res.torque_i;
          f = f + res.force;
          tq = tq + tw;
          const Vec3d m = cross(p - tr.origin(), res.force) + tw;
          const double add[6] = {res.force.x, res.force.y, res.force.z, m.x, m.y, m.z};
          for (std::size_t q = 0; q < 6; ++q) load[x.wall * 6 + q] += add[q];
        }
        if (keep_history) old = now;
      }
      force.x[i] = f.x;
      force.y[i] = f.y;
      force.z[i] = f.z;
      if (!g.spin) continue;
      torque.x[i] = tq.x;
      torque.y[i] = tq.y;
      torque.z[i] = tq.z;
    }
  });
  if (loads != nullptr) {
    std::vector<Vec3d> velocity(nw), spin(nw);
    for (std::size_t w = 0; w < nw; ++w) velocity[w] = turn[w].v, spin[w] = turn[w].spin;
    set_wall_loads(sums, *loads, velocity, spin);
  }
  return over;
}

}  // namespace

double mesh_wall_reach(const ContactTable& table) {
  double reach = 0.0;
  with_law(table.law(), [&]<class Law>() {
    if constexpr (ReachingLaw<Law>)
      for (std::size_t a = 0; a < table.types(); ++a)
        reach = std::max(reach, table.wall(a)[static_cast<std::size_t>(Law::kReach)]);
  });
  return reach;
}

MeshWall make_mesh_wall(std::string name, TriangleMesh mesh, double largest_radius) {
  MeshWall w;
  w.name = std::move(name);
  auto m = std::make_shared<TriangleMesh>(std::move(mesh));
  w.grid = std::make_shared<const TriangleGrid>(build_triangle_grid(*m, largest_radius));
  w.mesh = std::move(m);
  return w;
}

void attach_mesh_walls(World& world, const MeshWalls& walls) {
  Grains& g = world.grains;
  g.extras.attach<MeshWallForce>(g.n);
  g.extras.attach<MeshWallTorque>(g.n);
  g.extras.attach<MeshContactHistory>(g.n);
  world.resources.emplace<MeshWalls>(walls);
  world.resources.emplace<MeshWallLoads>();
}

template <class L>
bool compute_mesh_wall_forces(Grains& g, const MeshWalls& walls, bool rotation_enabled, const ContactTable& table,
                              double dt, double t_contact, double overlap_limit, bool keep_history,
                              std::vector<WallLoad>* loads) {
  return mesh_forces<L>(g, walls, rotation_enabled, table, dt, t_contact, overlap_limit, keep_history, loads);
}

std::vector<MeshContactPoint> mesh_contacts_of(const MeshWalls& walls, const Vec3d& p, double radius, double t,
                                               bool rotation_enabled) {
  std::vector<Turn> turn(walls.list.size());
  for (std::size_t w = 0; w < walls.list.size(); ++w)
    turn[w] = Turn(walls.list[w], t, rotation_enabled);
  Hit hits[kMeshSlots];
  const std::size_t nh = find_hits(walls, turn.data(), p, radius, hits);
  std::vector<MeshContactPoint> out;
  for (std::size_t h = 0; h < nh; ++h) {
    const Hit& x = hits[h];
    const Turn& tr = turn[x.wall];
    out.push_back({x.wall, x.tri, x.f, tr.to_world(x.q), -tr.vec(x.u, 1.0), x.d,
                   key_of(*walls.list[x.wall].mesh, x.wall, x.tri, x.f, x.u)});
  }
  return out;
}

void report_mesh_overlap(const Grains& g, const MeshWalls& walls, double limit, const StepContext& step, double t,
                         bool rotation_enabled) {
  double worst = -1.0;
  std::size_t at = 0, wall = 0, past = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double r = g.radius.r[i];
    for (const MeshContactPoint& c : mesh_contacts_of(walls, {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, r, t, rotation_enabled)) {
      const double ratio = (r - c.gap) / (2.0 * r);
      past += ratio > limit;
      if (ratio > worst) worst = ratio, at = i, wall = c.wall;
    }
  }
  const std::string name = walls.list.empty() ? std::string("a mesh wall") : "mesh wall '" + walls.list[wall].name + "'";
  throw StabilityError(std::string("grain ") + std::to_string(g.pid.id[at]) + " (row " + std::to_string(at) + ") overlaps " +
                       name + " by " + short_number(worst) + " of its diameter at step " + std::to_string(step.step) +
                       " (t = " + short_number(t) + " s, stage " + std::string(step.stage) + "), past run.max_overlap = " +
                       short_number(limit) + " (" + std::to_string(past) +
                       " mesh contacts past it). Fix: lower run.dt or the wall's omega, stiffen the wall contact "
                       "(kn), or check that the mesh is closed where grains press on it");
}

// The driver for every registered law: the table's external linkage makes the compiler emit them.
template <class... Laws>
constexpr auto mesh_wall_drivers(LawList<Laws...>) {
  return std::array{&compute_mesh_wall_forces<Laws>...};
}
extern const auto kMeshWallDrivers = mesh_wall_drivers(ContactLaws{});

}  // namespace gf
