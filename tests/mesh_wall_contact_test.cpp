// Sphere contacts with triangle-mesh walls: a sphere sliding and rolling across a finely triangulated plate feels
// the force history of the analytic plane of the same law (the linear and Hertz laws and the representative-volume
// law that acts before touching; still and rotating; along a path that runs exactly along shared edges and through
// shared vertices, and along a generic one); one contact on a convex edge and at a convex corner, two in a concave
// corner; the tangential spring carried from a triangle to its coplanar neighbour and over a shallow convex fold;
// the scene keys' errors; the mesh drum scene through the command line; a bit-identical checkpoint resume.
#include "systems/walls/mesh_wall_contact.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "systems/contact/laws.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "systems/walls/wall_contact.hpp"
#include "tests/test_support.hpp"

using gf::Grains;
using gf::Vec3d;

namespace {

constexpr double kR = 1.5e-3, kRho = 2500.0, kG = 9.81;
const double kM = kRho * 4.0 / 3.0 * std::numbers::pi * kR * kR * kR;
const double kI = 0.4 * kM * kR * kR;

double len(const Vec3d& v) { return std::sqrt(gf::dot(v, v)); }

// The wall constants of the seed's laws for one species (the walls of both kinds read the same table).
template <class Law>
gf::ContactTable table_of(double friction);

template <>
gf::ContactTable table_of<gf::LinearSpringDashpot>(double friction) {
  gf::LinearSpringDashpot::Params p;
  p.kn = 1000, p.kt = 600, p.kr = 1e-5, p.en = 0.5, p.et = 0.5, p.er = 0.5, p.friction = friction;
  p.rolling_friction = 5e-5;
  gf::ContactBody<gf::LinearSpringDashpot::Material> b{kM, kI, kR, {}, false};
  return gf::make_contact_table<gf::LinearSpringDashpot>({b}, {"glass"}, {p}, {p});
}

template <>
gf::ContactTable table_of<gf::HertzMindlin>(double friction) {
  gf::HertzMindlin::Params p;
  p.restitution = 0.5, p.friction = friction, p.rolling_friction = 0.01;
  gf::ContactBody<gf::HertzMindlin::Material> b{kM, kI, kR, {5e6, 0.3}, false};
  return gf::make_contact_table<gf::HertzMindlin>({b}, {"glass"}, {p}, {p});
}

// The representative-volume law acts before touching (it declares kReach): its wall constants with the defaults.
template <>
gf::ContactTable table_of<gf::RepresentativeVolume>(double) {
  gf::RepresentativeVolume::Params p;
  gf::ContactBody<gf::RepresentativeVolume::Material> b{kM, kI, kR, {}, false, kG};
  return gf::make_contact_table<gf::RepresentativeVolume>({b}, {"glass"}, {p}, {p});
}

// One spinning grain (row 0) with the columns both wall kinds use.
Grains one_grain() {
  Grains g;
  g.spin = true;
  g.resize(1);
  g.radius.r[0] = kR;
  g.mass.m[0] = kM;
  g.mass.inv_m[0] = 1.0 / kM;
  g.mass.inv_inertia[0] = 1.0 / kI;
  g.species.type[0] = 0;
  g.pid.id[0] = 0;
  g.extras.attach<gf::WallHistory>(1).shape(1, 1);
  g.extras.attach<gf::MeshWallForce>(1);
  g.extras.attach<gf::MeshWallTorque>(1);
  g.extras.attach<gf::MeshContactHistory>(1);
  return g;
}

void place(Grains& g, const Vec3d& x, const Vec3d& v, const Vec3d& w) {
  g.pos.x[0] = x.x, g.pos.y[0] = x.y, g.pos.z[0] = x.z;
  g.vel.x[0] = v.x, g.vel.y[0] = v.y, g.vel.z[0] = v.z;
  g.omega.x[0] = w.x, g.omega.y[0] = w.y, g.omega.z[0] = w.z;
}
Vec3d pos(const Grains& g) { return {g.pos.x[0], g.pos.y[0], g.pos.z[0]}; }

// The grid reaches the grain's radius and a law's reach beyond it (`beyond`, m).
gf::MeshWalls walls_of(gf::TriangleSoup soup, const Vec3d& rot_point = {0, 0, 0}, const Vec3d& rot_axis = {0, 0, 1},
                       double omega = 0.0, double beyond = 0.0) {
  gf::MeshWalls w;
  w.list.push_back(gf::make_mesh_wall("test mesh", gf::build_mesh(soup), kR + beyond));
  w.list.back().rot_point = rot_point;
  w.list.back().rot_axis = rot_axis;
  w.list.back().omega = omega;
  return w;
}

// Semi-implicit Euler on one grain under gravity -z and the given wall force and torque.
void step(Grains& g, const Vec3d& f, const Vec3d& t, double dt) {
  g.vel.x[0] += dt * f.x / kM;
  g.vel.y[0] += dt * f.y / kM;
  g.vel.z[0] += dt * (f.z / kM - kG);
  g.omega.x[0] += dt * t.x / kI;
  g.omega.y[0] += dt * t.y / kI;
  g.omega.z[0] += dt * t.z / kI;
  g.pos.x[0] += dt * g.vel.x[0];
  g.pos.y[0] += dt * g.vel.y[0];
  g.pos.z[0] += dt * g.vel.z[0];
}

struct Comparison {
  double force = 0, position = 0, spin = 0;  // largest differences over the run (N, m, rad/s)
  double force_scale = 0;                     // largest |F| seen on the plane
  double travelled = 0;                       // m
  std::size_t one_contact_steps = 0, steps = 0;
};

// The same grain run twice, against the analytic plane z = 0 and against a plate of 1 mm cells (triangles of 1 mm
// legs, 0.67 of the radius) in that plane, each step's force of one run integrated the same way as the other's.
template <class Law>
Comparison plane_versus_plate(const Vec3d& start, const Vec3d& v0, double omega, int steps, double dt) {
  const gf::ContactTable table = table_of<Law>(0.3);
  const Vec3d axis_point{0.001, 0.002, 0.0};
  gf::Walls plane;
  gf::Wall w;
  w.kind = gf::Wall::Kind::Plane;
  w.name = "plane";
  w.point = {0, 0, 0};
  w.normal = {0, 0, 1};
  w.rot_point = axis_point;
  w.rot_axis = {0, 0, 1};
  w.omega = omega;
  plane.list = {w};
  const double reach = gf::mesh_wall_reach(table);
  const gf::MeshWalls plate = walls_of(gf::plate_triangles({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.02, 0.02, 40, 40),
                                       axis_point, {0, 0, 1}, omega, reach);
  Grains a = one_grain(), b = one_grain();
  place(a, start, v0, {0, 0, 0});
  place(b, start, v0, {0, 0, 0});
  Comparison c;
  for (int k = 0; k < steps; ++k) {
    const double t = k * dt;
    gf::compute_wall_forces_scalar<Law>(a, plane, a.extras.get<gf::WallHistory>(), table, dt, t);
    gf::compute_mesh_wall_forces<Law>(b, plate, true, table, dt, t);
    const Vec3d fa{a.wall_force.x[0], a.wall_force.y[0], a.wall_force.z[0]};
    const Vec3d ta{a.wall_torque.x[0], a.wall_torque.y[0], a.wall_torque.z[0]};
    const auto& mf = b.extras.get<gf::MeshWallForce>();
    const auto& mt = b.extras.get<gf::MeshWallTorque>();
    const Vec3d fb{mf.x[0], mf.y[0], mf.z[0]}, tb{mt.x[0], mt.y[0], mt.z[0]};
    c.force = std::max(c.force, len(fa - fb));
    c.force_scale = std::max(c.force_scale, len(fa));
    c.one_contact_steps += gf::mesh_contacts_of(plate, pos(b), kR + reach, t).size() == 1;
    ++c.steps;
    step(a, fa, ta, dt);
    step(b, fb, tb, dt);
    c.position = std::max(c.position, len(pos(a) - pos(b)));
    c.spin = std::max(c.spin, len(Vec3d{a.omega.x[0] - b.omega.x[0], a.omega.y[0] - b.omega.y[0],
                                        a.omega.z[0] - b.omega.z[0]}));
  }
  c.travelled = len(pos(a) - start);
  return c;
}

std::size_t contacts_at(const gf::MeshWalls& w, const Vec3d& p) { return gf::mesh_contacts_of(w, p, kR, 0.0).size(); }

}  // namespace

// Tolerances. Both runs evaluate the same law on the same geometry; they differ only in how the gap and the normal
// are rounded (|p - q| from the closest point on a triangle against the plane's dot product: a few ulp of the
// 1.5 mm radius, ~1e-18 m against an overlap of ~3e-7 m). That is a relative difference of ~1e-12 in the normal
// force per step, which a dissipative contact does not amplify: over 6000 steps the forces agree to 1e-9 of the
// largest force and the paths to 1e-12 m. A lost tangential spring at one of the ~20 triangle edges crossed would
// instead change the tangential force by k_t |d_t| (~1e-5 N, 3 % of the weight) at once, and a doubled contact at a
// shared edge would double the normal force: both are many orders above the tolerance.
TEST_CASE("mesh wall: a sphere sliding and rolling across a fine plate feels the analytic plane's forces",
          "[mesh][contact]") {
  const double dt = 2e-5;  // 1/60 of the linear law's collision period, 1/40 of Hertz's at these speeds
  const double rest = kM * kG / 1000.0;
  struct Case {
    const char* what;
    Vec3d start, v0;
    double omega;
  };
  // The first path starts on a vertex and runs along the cells' diagonals, which are the triangles' shared edges,
  // through a vertex every 1.4 mm; the second crosses edges at generic points; the third has the plane and the
  // plate turning at 3 rad/s about an axis normal to them, so the wall's velocity omega x r drags the grain.
  const std::vector<Case> cases = {
      {"along shared edges and through vertices", {-0.005, -0.005, kR - rest}, {0.1, 0.1, 0}, 0.0},
      {"across edges at generic points", {-0.0052, -0.0031, kR - rest}, {0.12, 0.044, 0}, 0.0},
      {"on a turning plate", {-0.0041, 0.0013, kR - rest}, {0.05, -0.02, 0}, 3.0},
  };
  for (const Case& cs : cases) {
    const Comparison lsd = plane_versus_plate<gf::LinearSpringDashpot>(cs.start, cs.v0, cs.omega, 6000, dt);
    const Comparison hm = plane_versus_plate<gf::HertzMindlin>(cs.start, cs.v0, cs.omega, 6000, dt);
    // The law acting before touching: from its wall reach, at the plane's closest point (sphere_wall_surface).
    const Comparison rv = plane_versus_plate<gf::RepresentativeVolume>(cs.start, cs.v0, cs.omega, 6000, dt);
    for (const auto& [law, c] : {std::pair{"linear_spring_dashpot", lsd}, std::pair{"hertz_mindlin", hm},
                                 std::pair{"representative_volume", rv}}) {
      INFO(cs.what << ", " << law << ": force difference " << c.force << " N of " << c.force_scale
                   << " N, path difference " << c.position << " m over " << c.travelled << " m, spin difference "
                   << c.spin << " rad/s, one contact at " << c.one_contact_steps << " of " << c.steps << " steps");
      WARN(cs.what << ", " << law << ": largest force difference " << c.force / c.force_scale
                   << " of the largest force, path difference " << c.position << " m over " << c.travelled << " m");
      REQUIRE(c.travelled > 0.003);  // the path crosses at least 3 cells (1 mm)
      REQUIRE(c.one_contact_steps == c.steps);
      REQUIRE(c.force <= 1e-9 * c.force_scale);
      REQUIRE(c.position <= 1e-12);
      REQUIRE(c.spin <= 1e-9);
    }
  }
}

TEST_CASE("mesh wall: one contact on a convex edge and at a convex corner, two in a concave corner",
          "[mesh][contact]") {
  SECTION("a roof: two faces meeting at a convex ridge at 150 degrees") {
    const double L = 0.01, w = 0.01, h = w * std::tan(std::numbers::pi / 12);  // each face 15 degrees down
    const Vec3d r0{-L, 0, 0}, r1{L, 0, 0}, a0{-L, -w, -h}, a1{L, -w, -h}, b0{-L, w, -h}, b1{L, w, -h};
    gf::TriangleSoup s;
    s.add(r0, r1, a1, 1), s.add(r0, a1, a0, 2), s.add(r0, b0, b1, 3), s.add(r0, b1, r1, 4);
    const gf::MeshWalls roof = walls_of(s);
    // Sweep the grain over the ridge at 0.9 R from the roof: over face A, over the ridge (in the wedge between the
    // normals) and over face B. Always one contact, at the brute-force distance.
    const Vec3d na{0, -std::sin(std::numbers::pi / 12), std::cos(std::numbers::pi / 12)};
    const Vec3d nb{0, std::sin(std::numbers::pi / 12), std::cos(std::numbers::pi / 12)};
    std::vector<Vec3d> points;
    for (double y = -2e-3; y <= 0.0; y += 1e-4) points.push_back(Vec3d{3e-4, y, y * h / w} + 0.9 * kR * na);
    for (double f = 0.0; f <= 1.0; f += 0.05) {
      const Vec3d u = (1.0 - f) * na + f * nb;
      points.push_back(Vec3d{3e-4, 0, 0} + (0.9 * kR / len(u)) * u);
    }
    for (double y = 0.0; y <= 2e-3; y += 1e-4) points.push_back(Vec3d{3e-4, y, -y * h / w} + 0.9 * kR * nb);
    for (const Vec3d& p : points) {
      const auto c = gf::mesh_contacts_of(roof, p, kR, 0.0);
      INFO("grain at (" << p.x << ", " << p.y << ", " << p.z << ")");
      REQUIRE(c.size() == 1);
      REQUIRE(c[0].gap == Approx(0.9 * kR).epsilon(1e-9));
    }
    // Right above the ridge the contact is the edge's, its normal straight down.
    const auto c = gf::mesh_contacts_of(roof, {3e-4, 0, 0.9 * kR}, kR, 0.0);
    REQUIRE(c.size() == 1);
    REQUIRE(gf::is_edge(c[0].feature));
    REQUIRE(c[0].n.z == Approx(-1.0));
  }
  SECTION("a closed cube seen from outside: one contact at a face, an edge or a corner") {
    const double a = 0.005;
    const Vec3d v[8] = {{0, 0, 0}, {a, 0, 0}, {a, a, 0}, {0, a, 0}, {0, 0, a}, {a, 0, a}, {a, a, a}, {0, a, a}};
    const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {2, 3, 7, 6}, {1, 2, 6, 5}, {0, 4, 7, 3}};
    gf::TriangleSoup s;
    for (const auto& q : quads) {
      s.add(v[q[0]], v[q[1]], v[q[2]], s.size() + 1);
      s.add(v[q[0]], v[q[2]], v[q[3]], s.size() + 1);
    }
    const gf::MeshWalls cube = walls_of(s);
    const double d = 0.8 * kR;
    const Vec3d corner_dir = (1.0 / std::sqrt(3.0)) * Vec3d{1, 1, 1};
    const Vec3d edge_dir = (1.0 / std::sqrt(2.0)) * Vec3d{1, 0, 1};
    const auto corner = gf::mesh_contacts_of(cube, v[6] + d * corner_dir, kR, 0.0);
    REQUIRE(corner.size() == 1);
    REQUIRE(gf::is_vertex(corner[0].feature));
    REQUIRE(gf::dot(corner[0].n, corner_dir) == Approx(-1.0));
    const auto edge = gf::mesh_contacts_of(cube, Vec3d{a, 0.3 * a, a} + d * edge_dir, kR, 0.0);
    REQUIRE(edge.size() == 1);
    REQUIRE(gf::is_edge(edge[0].feature));
    // Over the diagonal of the top face (the two triangles' shared edge): one contact.
    REQUIRE(contacts_at(cube, Vec3d{0.4 * a, 0.4 * a, a + d}) == 1);
    // Near the corner but over the top face: one, the face's.
    const auto face = gf::mesh_contacts_of(cube, Vec3d{a - 1e-4, a - 2e-4, a + d}, kR, 0.0);
    REQUIRE(face.size() == 1);
    REQUIRE(face[0].feature == gf::Feature::Face);
  }
  SECTION("a floor and a wall meeting at a concave right angle, and a concave corner of three") {
    // The floor z = 0 for x in [0, 0.01], the wall x = 0 for z in [0, 0.01], the back wall y = 0; shared edges.
    gf::TriangleSoup s = gf::plate_triangles({0.005, 0.005, 0}, {0, 0, 1}, {1, 0, 0}, 0.005, 0.005, 4, 4);
    const gf::TriangleSoup wall = gf::plate_triangles({0, 0.005, 0.005}, {1, 0, 0}, {0, 0, -1}, 0.005, 0.005, 4, 4);
    const gf::TriangleSoup back = gf::plate_triangles({0.005, 0, 0.005}, {0, 1, 0}, {1, 0, 0}, 0.005, 0.005, 4, 4);
    for (const auto* o : {&wall, &back})
      for (std::size_t t = 0; t < o->size(); ++t)
        s.add(o->corners[3 * t], o->corners[3 * t + 1], o->corners[3 * t + 2], s.size() + 1);
    const gf::MeshWalls corner = walls_of(s);
    const auto two = gf::mesh_contacts_of(corner, {0.9 * kR, 0.004, 0.9 * kR}, kR, 0.0);
    REQUIRE(two.size() == 2);
    REQUIRE(two[0].gap == Approx(0.9 * kR));
    REQUIRE(two[1].gap == Approx(0.9 * kR));
    REQUIRE(std::abs(gf::dot(two[0].n, two[1].n)) < 1e-12);  // the floor's and the wall's normals
    REQUIRE(contacts_at(corner, {0.9 * kR, 0.9 * kR, 0.9 * kR}) == 3);
    // Away from the wall the floor alone.
    REQUIRE(contacts_at(corner, {0.004, 0.004, 0.9 * kR}) == 1);
  }
}

// The sphere is pressed on a plate and dragged along it at constant velocity with friction high enough that it
// sticks: the tangential spring then grows as v t, and the tangential force is -(k_t v t + eta_t v) without a
// reset wherever the contact passes from a triangle to the next.
TEST_CASE("mesh wall: the tangential spring is carried from a triangle to its coplanar neighbour", "[mesh][contact]") {
  const gf::ContactTable table = table_of<gf::LinearSpringDashpot>(100.0);
  const double kt = 600, eta_t = table.wall(0)[gf::LinearSpringDashpot::kEtaT];
  const gf::MeshWalls plate = walls_of(gf::plate_triangles({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.01, 0.01, 20, 20));
  Grains g = one_grain();
  const double dt = 1e-5, v = 0.05;
  const Vec3d start{-0.0031, -0.0007, kR - 1e-5};  // F_n = 0.01 N: the cap 100 F_n is never reached
  std::size_t keys = 0;
  std::uint64_t last_key = 0;
  for (int k = 0; k < 400; ++k) {  // 0.2 mm: over the diagonal edge and a cell's side (cells 1 mm wide)
    place(g, start + Vec3d{v * k * dt, 0.3 * v * k * dt, 0}, {v, 0.3 * v, 0}, {0, 0, 0});
    gf::compute_mesh_wall_forces<gf::LinearSpringDashpot>(g, plate, true, table, dt, 0.0);
    const auto& f = g.extras.get<gf::MeshWallForce>();
    const double speed = v * std::sqrt(1.09);
    const double expect = kt * speed * (k + 1) * dt + eta_t * speed;
    const double ft = std::hypot(f.x[0], f.y[0]);
    INFO("step " << k);
    REQUIRE(ft == Approx(expect).epsilon(1e-9));
    const std::uint64_t key = gf::mesh_contacts_of(plate, pos(g), kR, 0.0).front().key;
    keys += key != last_key;
    last_key = key;
  }
  REQUIRE(keys == 1);  // one flat region: one key throughout
  // The path did cross triangles: the grain's projection moved 0.2 mm across the 1 mm cells from x = -3.1 mm.
  const auto first = gf::mesh_contacts_of(plate, start, kR, 0.0).front().triangle;
  const auto last = gf::mesh_contacts_of(plate, pos(g), kR, 0.0).front().triangle;
  REQUIRE(first != last);
}

TEST_CASE("mesh wall: the tangential spring is carried over a shallow convex fold", "[mesh][contact]") {
  // Two plates meeting at x = 0 with a 4 degree fold; the grain is dragged over the fold, sticking.
  const double th = 4.0 * std::numbers::pi / 180.0;
  const Vec3d r0{0, -0.01, 0}, r1{0, 0.01, 0}, a0{-0.01, -0.01, 0}, a1{-0.01, 0.01, 0};
  const Vec3d b0{0.01 * std::cos(th), -0.01, -0.01 * std::sin(th)}, b1{0.01 * std::cos(th), 0.01, -0.01 * std::sin(th)};
  gf::TriangleSoup s;
  s.add(a0, r0, r1, 1), s.add(a0, r1, a1, 2), s.add(r0, b0, b1, 3), s.add(r0, b1, r1, 4);
  const gf::MeshWalls fold = walls_of(s);
  const gf::ContactTable table = table_of<gf::LinearSpringDashpot>(100.0);
  Grains g = one_grain();
  const double dt = 1e-5, v = 0.5;  // 1 mm in 200 steps; at 0.1 mm overlap the cap 100 F_n = 10 N is not reached
  double previous = 0.0;
  std::size_t keys = 0;
  std::uint64_t last = 0;
  for (int k = 0; k < 200; ++k) {
    // Along the surface at 0.1 mm overlap: over face A, then over face B.
    const double x = -5e-4 + v * k * dt;
    const Vec3d out = x <= 0 ? Vec3d{0, 0, 1} : Vec3d{std::sin(th), 0, std::cos(th)};
    const Vec3d surf = x <= 0 ? Vec3d{x, 0, 0} : Vec3d{x * std::cos(th), 0, -x * std::sin(th)};
    place(g, surf + (kR - 1e-4) * out, {v, 0, 0}, {0, 0, 0});
    gf::compute_mesh_wall_forces<gf::LinearSpringDashpot>(g, fold, true, table, dt, 0.0);
    const auto c = gf::mesh_contacts_of(fold, pos(g), kR, 0.0);
    REQUIRE(c.size() == 1);
    keys += c[0].key != last;
    last = c[0].key;
    const auto& f = g.extras.get<gf::MeshWallForce>();
    const Vec3d fv{f.x[0], f.y[0], f.z[0]};
    const double ft = len(fv - gf::dot(fv, c[0].n) * c[0].n);
    INFO("step " << k << ": tangential force " << ft << " N, before " << previous << " N");
    REQUIRE(ft >= previous);  // grows throughout: never reset to the first step's value
    previous = ft;
  }
  // Two flat regions, and on the ridge itself (one step lands within rounding of it) the edge's own key: the spring
  // passed from one slot key to the next by the nearness of the normals.
  REQUIRE(keys >= 2);
  REQUIRE(keys <= 3);
}

// ---- Scenes --------------------------------------------------------------------------------------------------

namespace {

namespace fs = std::filesystem;

const fs::path kMeshDrum = fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/tests/mesh_drum.toml";

// A small scene around one mesh wall given by `wall` (the lines of its [[wall]] table).
std::string scene_with(const std::string& wall) {
  return "[run]\ndt = 3.0e-5\nduration = 0.001\nskin = 3.0e-4\ngravity = [0.0, -9.81, 0.0]\n\n"
         "[[species]]\nname = \"glass\"\ndiameter = 2.0e-3\ndensity = 2500.0\n\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nen = 0.3\net = 0.3\nfriction = 0.3\n\n"
         "[[wall]]\ntype = \"mesh\"\n" +
         wall +
         "\n[[fill]]\nkind = \"random\"\n"
         "region = { shape = \"box\", lo = [-0.01, 0.005, -0.01], hi = [0.01, 0.015, 0.01] }\ncount = { glass = 20 }\n";
}

std::string load_error(const fs::path& scene) {
  try {
    gf::DemSimulation::from_file(scene);
  } catch (const gf::SceneError& e) {
    return e.what();
  }
  return "";
}

// "<scene>:<line>:" of the first line holding `key =`, or for a missing key of its table, [[wall]].
std::string at_key(const fs::path& scene, const std::string& text, const std::string& key) {
  const auto lines = gf::test::lines_of(text);
  for (const std::string& k : {key + " =", std::string("[[wall]]")})
    for (std::size_t n = 0; n < lines.size(); ++n)
      if (lines[n].rfind(k, 0) == 0) return scene.string() + ":" + std::to_string(n + 1) + ":";
  return "no line holds " + key;
}

const std::string kFloor = "primitive = \"plate\"\ncenter = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\n"
                           "axis = [1.0, 0.0, 0.0]\nhalf_widths = [0.02, 0.02]\ncells = [4, 4]\n";

}  // namespace

TEST_CASE("mesh wall scene: bad mesh input is refused naming the scene line, the key, the mesh's place and the fix",
          "[mesh][scene]") {
  gf::test::TempDir dir("mesh_scene_errors");
  auto check = [&](const std::string& wall, const std::string& key, const std::vector<std::string>& parts) {
    const std::string text = scene_with(wall);
    const fs::path scene = dir.write("scene.toml", text);
    const std::string m = load_error(scene);
    INFO(m);
    CHECK_THAT(m, Catch::Contains(at_key(scene, text, key)));
    CHECK_THAT(m, Catch::Contains("key 'wall[0]." + key + "'"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
    for (const std::string& p : parts) CHECK_THAT(m, Catch::Contains(p));
  };
  SECTION("missing file") { check("file = \"nowhere.stl\"\n", "file", {"nowhere.stl"}); }
  SECTION("truncated binary file") {
    const gf::TriangleSoup plate = gf::plate_triangles({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 0.01, 0.01, 2, 2);
    gf::write_stl_binary(dir.path / "cut.stl", plate);
    const std::string bytes = gf::test::read_file(dir.path / "cut.stl");
    dir.write("cut.stl", bytes.substr(0, bytes.size() - 7));
    check("file = \"cut.stl\"\n", "file", {"cut.stl", "truncated"});
  }
  SECTION("degenerate triangle, with its line in the STL file") {
    dir.write("flat.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 2 0 0\n"
                          "endloop\nendfacet\nendsolid s\n");
    check("file = \"flat.stl\"\n", "file", {"flat.stl:2:", "degenerate"});
  }
  SECTION("no triangles") {
    dir.write("empty.stl", "solid s\nendsolid s\n");
    check("file = \"empty.stl\"\n", "file", {"empty.stl", "no triangles"});
  }
  SECTION("a NaN in the file") {
    dir.write("nan.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 NaN\nvertex 0 1 0\n"
                         "endloop\nendfacet\nendsolid s\n");
    check("file = \"nan.stl\"\n", "file", {"nan.stl:5:", "finite"});
  }
  SECTION("neither file nor primitive") { check("name = \"x\"\nomega = 0.0\n", "file", {"exactly one of"}); }
  SECTION("a turning file without its axis") {
    gf::write_stl_ascii(dir.path / "plate.stl", gf::plate_triangles({0, 0, 0}, {0, 1, 0}, {1, 0, 0}, 0.01, 0.01, 1, 1));
    check("file = \"plate.stl\"\nomega = 1.0\n", "rotation_axis", {"rotation axis"});
  }
  SECTION("a mesh turning so fast it would pass through grains") {
    check(kFloor + "omega = 1.0e4\n", "omega", {"per step"});
  }
  SECTION("a plate whose axis is its normal") {
    check("primitive = \"plate\"\ncenter = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]\naxis = [0.0, 2.0, 0.0]\n"
          "half_widths = [0.02, 0.02]\n",
          "axis", {"normal"});
  }
  SECTION("a fill reaching through a mesh wall") {
    const std::string text = scene_with("primitive = \"plate\"\ncenter = [0.0, 0.01, 0.0]\nnormal = [0.0, 1.0, 0.0]\n"
                                        "axis = [1.0, 0.0, 0.0]\nhalf_widths = [0.02, 0.02]\n");
    const fs::path scene = dir.write("scene.toml", text);
    const std::string m = load_error(scene);
    CHECK_THAT(m, Catch::Contains("mesh wall 'mesh'"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
  }
}

TEST_CASE("mesh wall scene: grainflow check and run accept the mesh drum and refuse a bad mesh", "[mesh][scene][cli]") {
  gf::test::TempDir dir("mesh_scene_cli");
  const gf::test::Exit check = gf::test::run_cli(dir, "check " + gf::test::quote(kMeshDrum.string()));
  INFO(check.err);
  REQUIRE(check.code == 0);
  CHECK_THAT(check.out + check.err, Catch::Contains("mesh_wall_contact"));
  const fs::path out = dir.path / "out";
  const gf::test::Exit run = gf::test::run_cli(
      dir, "run " + gf::test::quote(kMeshDrum.string()) + " --out " + gf::test::quote(out.string()) + " --quiet");
  INFO(run.err);
  REQUIRE(run.code == 0);
  REQUIRE(fs::exists(out / "summary.json"));
  // The series counts the mesh contacts (the pour has reached the mantle by the last row) and gives the
  // mesh drum's angle, omega t, as for an analytic drum.
  const auto rows = gf::test::read_lines(out / "series.csv");
  REQUIRE(rows.size() > 2);
  std::vector<double> last;
  {
    std::stringstream ss(rows.back());
    std::string cell;
    while (std::getline(ss, cell, ',')) last.push_back(std::stod(cell));
  }
  REQUIRE(last.size() >= 6);
  CHECK(last[1] == Approx(1.5 * last[0]).epsilon(1e-12));
  CHECK(last[5] > 0);
  // Poured and settled for 0.15 s (the grains fall at most 3 cm onto the mantle and come to rest on it), then
  // turned: every grain stays inside the drum's mesh surfaces and the bed lies on the mantle.
  gf::DemSimulation sim = gf::DemSimulation::from_file(kMeshDrum, {"settle.time=0.15"});
  sim.settle(0.0);
  sim.advance(300);
  const Grains& g = sim.grains();
  double worst = -1.0;
  std::size_t on_mantle = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double rho = std::hypot(g.pos.x[i], g.pos.y[i]);
    worst = std::max({worst, rho + g.radius.r[i] - 0.04, std::abs(g.pos.z[i]) + g.radius.r[i] - 0.008});
    on_mantle += rho + g.radius.r[i] > 0.04 - 1e-4;
  }
  INFO("largest reach past the drum's surfaces " << worst << " m, " << on_mantle << " grains on the mantle");
  // Overlaps under a few grain layers are ~ m g / k_n times the layers, 1e-6 m; 0.1 mm would be a grain through.
  CHECK(worst < 1e-4);
  CHECK(on_mantle >= 20);

  // A bad mesh file under check: exit 1 with the scene's line, the key and the file.
  const std::string text = scene_with("file = \"missing.stl\"\n");
  const fs::path bad = dir.write("bad.toml", text);
  const gf::test::Exit e = gf::test::run_cli(dir, "check " + gf::test::quote(bad.string()));
  REQUIRE(e.exited);
  CHECK(e.code == 1);
  CHECK_THAT(e.err, Catch::Contains(at_key(bad, text, "file")) && Catch::Contains("key 'wall[0].file'") &&
                        Catch::Contains("missing.stl"));
}

// The mesh contacts' springs are attached grain columns: a checkpoint carries them, and a run resumed from it
// continues bit for bit (forces, springs and paths), as for the analytic walls.
TEST_CASE("mesh wall scene: a run resumed from a checkpoint continues bit for bit", "[mesh][scene][checkpoint]") {
  gf::test::TempDir dir("mesh_ckpt");
  const std::vector<std::string> set = {"settle.time=0.12"};
  auto whole = gf::DemSimulation::from_file(kMeshDrum, set);
  whole.settle(0.0);
  whole.advance(600);
  auto first = gf::DemSimulation::from_file(kMeshDrum, set);
  first.settle(0.0);
  first.advance(300);
  gf::CheckpointWriter w;
  gf::save_dem_state(w, first.world(), first.scene());
  w.write(dir.path / "c.gfc");
  auto resumed = gf::DemSimulation::from_file(kMeshDrum, set);
  resumed.resume(gf::CheckpointReader(dir.path / "c.gfc"));
  resumed.advance(300);
  Grains& a = whole.grains();
  Grains& b = resumed.grains();
  REQUIRE(a.n == b.n);
  std::size_t touching = 0;
  const auto& ha = a.extras.get<gf::MeshContactHistory>().slots;
  const auto& hb = b.extras.get<gf::MeshContactHistory>().slots;
  for (std::size_t i = 0; i < a.n; ++i) {
    INFO("row " << i);
    REQUIRE(a.pos.x[i] == b.pos.x[i]);
    REQUIRE(a.pos.y[i] == b.pos.y[i]);
    REQUIRE(a.pos.z[i] == b.pos.z[i]);
    REQUIRE(std::memcmp(&ha[i], &hb[i], sizeof(gf::MeshSlots)) == 0);
    touching += ha[i].key[0] != 0;
  }
  REQUIRE(touching >= 20);  // the comparison covered grains with mesh springs
}
