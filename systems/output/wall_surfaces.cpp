#include "systems/output/wall_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "systems/output/vtk_appended.hpp"

namespace gf {

namespace {

constexpr int kSegments = 96;  // around a cylinder's mantle

// A wall's or mesh's rigid placement at one time: X -> o + d + R(angle)(X - o).
struct RigidPlacement {
  Vec3d o{0, 0, 0}, axis{0, 0, 1}, d{0, 0, 0};
  double angle = 0.0;
  Vec3d point(const Vec3d& x) const { return o + d + rotate_about(x - o, axis, angle); }
};

void grow_box(SceneBox& b, const Vec3d& p) {
  b.lo = {std::min(b.lo.x, p.x), std::min(b.lo.y, p.y), std::min(b.lo.z, p.z)};
  b.hi = {std::max(b.hi.x, p.x), std::max(b.hi.y, p.y), std::max(b.hi.z, p.z)};
}

// Unit vectors u, v with (u, v, n) right-handed.
void plane_basis(const Vec3d& n, Vec3d& u, Vec3d& v) {
  const Vec3d trial = std::abs(n.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  u = trial - dot(trial, n) * n;
  u = (1.0 / std::sqrt(dot(u, u))) * u;
  v = cross(n, u);
}

// A convex polygon (its points in order) as a fan of triangles.
void add_polygon(WallSurface& s, const std::vector<Vec3d>& poly, std::int32_t wall) {
  if (poly.size() < 3) return;
  const auto first = static_cast<std::uint32_t>(s.points.size());
  s.points.insert(s.points.end(), poly.begin(), poly.end());
  for (std::uint32_t k = 1; k + 1 < poly.size(); ++k) {
    s.triangles.push_back({first, first + k, first + k + 1});
    s.wall.push_back(wall);
  }
}

// Where the plane through p with unit normal n crosses the box: its edges' crossings, in order around
// their centre.
std::vector<Vec3d> plane_in_box(const Vec3d& p, const Vec3d& n, const SceneBox& b) {
  const Vec3d c[8] = {{b.lo.x, b.lo.y, b.lo.z}, {b.hi.x, b.lo.y, b.lo.z}, {b.lo.x, b.hi.y, b.lo.z},
                      {b.hi.x, b.hi.y, b.lo.z}, {b.lo.x, b.lo.y, b.hi.z}, {b.hi.x, b.lo.y, b.hi.z},
                      {b.lo.x, b.hi.y, b.hi.z}, {b.hi.x, b.hi.y, b.hi.z}};
  std::vector<Vec3d> out;
  for (int i = 0; i < 8; ++i)
    for (int bit = 1; bit < 8; bit <<= 1) {
      if ((i & bit) != 0) continue;
      const int j = i | bit;
      const double si = dot(c[i] - p, n), sj = dot(c[j] - p, n);
      if ((si < 0.0) == (sj < 0.0) && si != 0.0) continue;
      if (si == sj) continue;
      out.push_back(c[i] + (si / (si - sj)) * (c[j] - c[i]));
    }
  if (out.size() < 3) return {};
  Vec3d mid{0, 0, 0};
  for (const Vec3d& q : out) mid = mid + q;
  mid = (1.0 / static_cast<double>(out.size())) * mid;
  Vec3d u, v;
  plane_basis(n, u, v);
  std::sort(out.begin(), out.end(), [&](const Vec3d& a, const Vec3d& q) {
    return std::atan2(dot(a - mid, v), dot(a - mid, u)) < std::atan2(dot(q - mid, v), dot(q - mid, u));
  });
  return out;
}

void add_cylinder(WallSurface& s, const Wall& w, const SceneBox& b, std::int32_t wall) {
  double lo = -0.5 * w.length, hi = 0.5 * w.length;
  if (w.length <= 0.0) {  // across the scene's box along the axis
    lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < 8; ++i) {
      const Vec3d c{(i & 1) ? b.hi.x : b.lo.x, (i & 2) ? b.hi.y : b.lo.y, (i & 4) ? b.hi.z : b.lo.z};
      const double a = dot(c - w.cur_center, w.cur_axis);
      lo = std::min(lo, a), hi = std::max(hi, a);
    }
  }
  Vec3d u, v;
  plane_basis(w.cur_axis, u, v);
  const auto first = static_cast<std::uint32_t>(s.points.size());
  for (int k = 0; k < kSegments; ++k) {
    const double a = 2.0 * std::numbers::pi * k / kSegments;
    const Vec3d r = (w.radius * std::cos(a)) * u + (w.radius * std::sin(a)) * v;
    s.points.push_back(w.cur_center + r + lo * w.cur_axis);
    s.points.push_back(w.cur_center + r + hi * w.cur_axis);
  }
  for (std::uint32_t k = 0; k < kSegments; ++k) {
    const std::uint32_t a = first + 2 * k, next = first + 2 * ((k + 1) % kSegments);
    s.triangles.push_back({a, next, a + 1});
    s.triangles.push_back({a + 1, next, next + 1});
    s.wall.push_back(wall);
    s.wall.push_back(wall);
  }
}

RigidPlacement mesh_placement(const MeshWall& m, double t, bool enabled) {
  RigidPlacement p{m.rot_point, m.rot_axis, {0, 0, 0}, enabled ? m.omega * t : 0.0};
  if (enabled) p.d = m.motion.offset(t);
  return p;
}

}  // namespace

SceneBox scene_box(const Grains& g, const Walls& walls, const MeshWalls* meshes) {
  std::vector<Vec3d> points(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i) points[i] = {g.pos.x[i], g.pos.y[i], g.pos.z[i]};
  return scene_box(points, walls, meshes);
}

SceneBox scene_box(const std::vector<Vec3d>& points, const Walls& walls, const MeshWalls* meshes) {
  SceneBox b{{INFINITY, INFINITY, INFINITY}, {-INFINITY, -INFINITY, -INFINITY}};
  for (const Vec3d& p : points) grow_box(b, p);
  for (const Wall& w : walls.list) {
    for (const Vec3d& p : w.outline) grow_box(b, p);
    // An unbounded plane: its point, so that the box reaches the plane (a container's side).
    if (w.kind == Wall::Kind::Plane && w.outline.empty()) grow_box(b, w.point);
    if (w.kind == Wall::Kind::CylinderInner && w.length > 0.0)
      for (const double s : {-0.5, 0.5})
        for (const double r : {-1.0, 1.0}) {
          Vec3d u, v;
          plane_basis(w.axis, u, v);
          grow_box(b, w.center + (s * w.length) * w.axis + (r * w.radius) * u);
          grow_box(b, w.center + (s * w.length) * w.axis + (r * w.radius) * v);
        }
  }
  if (meshes != nullptr)
    for (const MeshWall& m : meshes->list)
      for (const Vec3d& p : m.mesh->vertex) grow_box(b, p);
  if (!(b.lo.x <= b.hi.x)) return {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};  // nothing to size it by: a metre
  const double side = std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z, 1e-3});
  const Vec3d m{0.1 * side, 0.1 * side, 0.1 * side};
  return {b.lo - m, b.hi + m};
}

WallSurface wall_surface(const Walls& given, const MeshWalls* meshes, double t, const SceneBox& box) {
  Walls walls = given;  // placed at t here, whatever time the contacts last placed them at
  walls.place(t);
  WallSurface s;
  std::int32_t index = 0;
  for (std::size_t k = 0; k < walls.list.size(); ++k, ++index) {
    const Wall& w = walls.list[k];
    if (w.kind == Wall::Kind::CylinderInner) {
      add_cylinder(s, w, box, index);
      continue;
    }
    if (w.outline.empty()) {
      add_polygon(s, plane_in_box(w.cur_point, w.cur_normal, box), index);
      continue;
    }
    const RigidPlacement p{w.rot_point, w.rot_axis, w.cur_origin - w.rot_point, walls.angle(k, t)};
    std::vector<Vec3d> poly;
    for (const Vec3d& x : w.outline) poly.push_back(p.point(x));
    add_polygon(s, poly, index);
  }
  if (meshes == nullptr) return s;
  for (const MeshWall& m : meshes->list) {
    const RigidPlacement p = mesh_placement(m, t, walls.rotation_enabled);
    const auto first = static_cast<std::uint32_t>(s.points.size());
    for (const Vec3d& x : m.mesh->vertex) s.points.push_back(p.point(x));
    for (const auto& tri : m.mesh->tri) {
      s.triangles.push_back({first + tri[0], first + tri[1], first + tri[2]});
      s.wall.push_back(index);
    }
    ++index;
  }
  return s;
}

bool walls_move(const Walls& walls, const MeshWalls* meshes) {
  for (const Wall& w : walls.list)
    if (w.omega != 0.0 || w.motion.moves()) return true;
  if (meshes != nullptr)
    for (const MeshWall& m : meshes->list)
      if (m.omega != 0.0 || m.motion.moves()) return true;
  return false;
}

std::string wall_surface_vtp(const WallSurface& s) {
  vtk::AppendedArrays data;
  const std::size_t np = s.points.size(), nt = s.triangles.size();
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"";
  xml += vtk::kByteOrder;
  xml += "\" header_type=\"UInt64\">\n  <PolyData>\n";
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(np) +
         "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"" + std::to_string(nt) +
         "\">\n";
  const std::string_view in = "        ";
  xml += "      <CellData Scalars=\"wall\">\n";
  data.add<std::int32_t>(xml, in, "wall", 1, nt, [&](std::size_t i, std::size_t) { return s.wall[i]; });
  xml += "      </CellData>\n      <Points>\n";
  data.add<double>(xml, in, "Points", 3, np, [&](std::size_t i, std::size_t c) {
    const Vec3d& p = s.points[i];
    return c == 0 ? p.x : (c == 1 ? p.y : p.z);
  });
  xml += "      </Points>\n      <Polys>\n";
  data.add<std::int64_t>(xml, in, "connectivity", 1, 3 * nt,
                         [&](std::size_t i, std::size_t) { return static_cast<std::int64_t>(s.triangles[i / 3][i % 3]); });
  data.add<std::int64_t>(xml, in, "offsets", 1, nt,
                         [](std::size_t i, std::size_t) { return static_cast<std::int64_t>(3 * (i + 1)); });
  xml += "      </Polys>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n   _";
  xml += data.blob();
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

}  // namespace gf
