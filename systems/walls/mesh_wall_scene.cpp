#include "systems/walls/mesh_wall_scene.hpp"

#include <algorithm>
#include <cmath>

#include "systems/walls/wall_fields.hpp"

namespace gf {

namespace {

Vec3d to_v(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

Vec3d direction(const SceneNode& node, std::string_view key, const Vec3d* fallback) {
  const std::array<double, 3> a =
      fallback ? node.get_vec3(key, {fallback->x, fallback->y, fallback->z}) : node.get_vec3(key);
  const double len = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  if (!(len > 0.0)) node.fail(key, "a direction must not be the zero vector", "give a non-zero vector, e.g. [0, 0, 1]");
  return {a[0] / len, a[1] / len, a[2] / len};
}

// The wall table's field named `key`, for the keys read below.
const Field& field(std::string_view key) { return kWallFields.field(key); }

int count(const SceneNode& w, std::string_view key) { return static_cast<int>(read_integer(w, field(key))); }

// A MeshError's "<where>: <problem>. Fix: <fix>" as the scene's message at `key`.
[[noreturn]] void fail_mesh(const SceneNode& w, std::string_view key, const MeshError& e) {
  const std::string m = e.what();
  const std::size_t at = m.rfind(". Fix: ");
  if (at == std::string::npos) w.fail(key, "the mesh cannot be used: " + m, "check the mesh");
  w.fail(key, "the mesh cannot be used: " + m.substr(0, at), m.substr(at + 7));
}

TriangleSoup primitive(const SceneNode& w, const std::string& kind, Vec3d& axis_out, Vec3d& center_out) {
  const Vec3d center = to_v(w.get_vec3(field("center").key));
  center_out = center;
  if (kind == "plate") {
    const Vec3d normal = direction(w, field("normal").key, nullptr);
    const Vec3d axis = direction(w, field("axis").key, nullptr);
    if (std::abs(dot(axis, normal)) > 0.999)
      w.fail("axis", "the plate's in-plane axis is (nearly) along its normal",
             "give an axis in the plate's plane, perpendicular to normal");
    const std::vector<double> half = w.get_doubles(field("half_widths").key);
    if (half.size() != 2 || !(half[0] > 0 && half[1] > 0 && half[0] <= 1e3 && half[1] <= 1e3))
      w.fail("half_widths", "give the plate's two half-widths as [a, b], each > 0 and at most 1000 (m)",
             "e.g. half_widths = [0.05, 0.02]");
    std::vector<double> cells{1.0, 1.0};
    if (w.has(field("cells").key)) cells = w.get_doubles("cells");
    if (cells.size() != 2 || cells[0] != std::floor(cells[0]) || cells[1] != std::floor(cells[1]) || cells[0] < 1 ||
        cells[1] < 1 || cells[0] * cells[1] > 1e7)
      w.fail("cells", "give the plate's cells as two whole numbers [n_a, n_b], each at least 1 (at most 10^7 cells)",
             "e.g. cells = [4, 2]");
    axis_out = normal;
    return plate_triangles(center, normal, axis, half[0], half[1], static_cast<int>(cells[0]),
                           static_cast<int>(cells[1]));
  }
  const Vec3d axis = direction(w, field("axis").key, nullptr);
  axis_out = axis;
  if (kind == "annulus") {
    const double outer = read_number(w, field("outer_radius"));
    const double inner = read_number(w, field("inner_radius"));
    if (!(inner < outer))
      w.fail("inner_radius", "the inner radius " + short_number(inner) + " m is not below the outer radius " +
                                 short_number(outer) + " m",
             "give inner_radius < outer_radius (0 for a full disc)");
    return annulus_triangles(center, axis, inner, outer, count(w, "segments"));
  }
  const double radius = read_number(w, field("radius"));
  const double length = read_number(w, field("length"));
  return cylinder_triangles(center, axis, radius, length, count(w, "segments"), count(w, "rings"));
}

}  // namespace

MeshWall read_mesh_wall(const SceneNode& w, const std::string& name, double largest_radius, double smallest_diameter,
                        double dt) {
  const bool has_file = w.has(field("file").key), has_primitive = w.has(field("primitive").key);
  if (has_file == has_primitive)
    w.fail(has_file ? "primitive" : "file", "a mesh wall takes exactly one of 'file' (an STL file) and 'primitive'",
           "give file = \"part.stl\" (relative to the scene file), or primitive = \"plate\", \"annulus\" or "
           "\"cylinder\" with its keys");
  TriangleSoup soup;
  Vec3d default_axis{0, 0, 1}, default_point{0, 0, 0};
  bool defaults = false;
  const char* key = has_file ? "file" : "primitive";
  if (has_file) {
    const std::string file = w.get_string("file");
    const double scale = read_number(w, field("scale"));
    const Vec3d translate = to_v(w.get_vec3(field("translate").key, {0, 0, 0}));
    try {
      soup = read_stl(w.doc().resolve(file));
    } catch (const MeshError& e) {
      fail_mesh(w, "file", e);
    }
    transform_soup(soup, scale, translate);
  } else {
    const std::string kind = w.get_choice("primitive", {"plate", "annulus", "cylinder"});
    soup = primitive(w, kind, default_axis, default_point);
    soup.name = "the " + kind + " of " + w.path();
    defaults = true;
  }
  MeshWall mw;
  try {
    mw = make_mesh_wall(name, build_mesh(soup), largest_radius);
  } catch (const MeshError& e) {
    fail_mesh(w, key, e);
  }
  mw.omega = read_number(w, field("omega"));
  if (mw.omega != 0.0 && !defaults) {
    if (!w.has("rotation_axis"))
      w.fail("rotation_axis", "a turning mesh from a file needs its rotation axis",
             "give rotation_axis = [x, y, z] and rotation_point = [x, y, z] (m)");
    if (!w.has("rotation_point"))
      w.fail("rotation_point", "a turning mesh from a file needs a point on its rotation axis",
             "give rotation_point = [x, y, z] (m)");
  }
  mw.rot_axis = direction(w, field("rotation_axis").key, &default_axis);
  mw.rot_point = to_v(w.get_vec3(field("rotation_point").key, {default_point.x, default_point.y, default_point.z}));
  // The fastest surface point: omega times the largest distance of a vertex from the axis.
  double reach = 0.0;
  for (const Vec3d& v : mw.mesh->vertex) {
    const Vec3d q = v - mw.rot_point;
    const Vec3d radial = q - dot(q, mw.rot_axis) * mw.rot_axis;
    reach = std::max(reach, std::sqrt(dot(radial, radial)));
  }
  const double step = std::abs(mw.omega) * reach * dt;
  if (step > 0.1 * smallest_diameter)
    w.fail("omega", "the mesh's farthest point from its axis (" + short_number(reach) + " m) moves " +
                        short_number(step) + " m per step, more than 0.1 of the smallest diameter (" +
                        short_number(smallest_diameter) + " m)",
           "lower omega (rad/s) or run.dt, or check scale (a file in mm needs scale = 0.001)");
  return mw;
}

const MeshWall* overlapped_mesh_wall(const MeshWalls& walls, const Vec3d& p, double r) {
  const std::vector<MeshContactPoint> c = mesh_contacts_of(walls, p, r, 0.0, false);
  return c.empty() ? nullptr : &walls.list[c.front().wall];
}

}  // namespace gf
