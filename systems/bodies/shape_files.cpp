#include "systems/bodies/shape_files.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <optional>
#include <set>
#include <system_error>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "engine/read_file.hpp"
#include "engine/scene.hpp"
#include "engine/user_text.hpp"

namespace gf {

namespace {

using Eigen::Vector3d;

// Where a file's problem lies: a line (text) or a triangle (binary STL).
struct Source {
  std::string name;
  bool triangles = false;

  std::string at(std::size_t n) const {
    if (n == 0) return name;
    return triangles ? name + ": triangle " + std::to_string(n) : name + ":" + std::to_string(n);
  }
  [[noreturn]] void fail(std::size_t n, const std::string& problem, const std::string& fix) const {
    throw ShapeFileError(at(n) + ": " + problem + ". Fix: " + fix);
  }
};

using Triangle = std::array<std::uint32_t, 3>;

// A part as read: its vertices, where each was read, its faces as triangles of them (polygons fanned;
// none when the file has no faces) and where each was read, and where the part begins.
struct RawPart {
  std::string label;  // as messages name it: part 'name', or piece k of solid 'name'
  std::size_t at = 0;
  std::vector<Vector3d> v;
  std::vector<std::size_t> v_at;
  std::vector<Triangle> tris;
  std::vector<std::size_t> tri_at;
};

constexpr std::size_t kMaxFileVertices = kMaxShapeParts * kMaxCoreVertices;
// A convex surface of n vertices has at most 2n - 4 triangles; more are repeated or folded faces.
constexpr std::size_t kMaxPartTriangles = 16 * kMaxCoreVertices;
constexpr std::size_t kMaxFileTriangles = kMaxShapeParts * kMaxPartTriangles;

double bounding_diagonal(const std::vector<Vector3d>& v) {
  Vector3d lo = v.front(), hi = v.front();
  for (const Vector3d& x : v) lo = lo.cwiseMin(x), hi = hi.cwiseMax(x);
  return (hi - lo).norm();
}

// The affine dimension of a point set (0 point, 1 line, 2 plane, 3 solid), within 1e-6 of its size.
int affine_dimension(const std::vector<Vector3d>& v) {
  auto farthest = [&](auto&& dist) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < v.size(); ++i)
      if (dist(v[i]) > dist(v[best])) best = i;
    return v[best];
  };
  const Vector3d a = v.front();
  const Vector3d b = farthest([&](const Vector3d& x) { return (x - a).norm(); });
  const double tol = 1e-6 * (b - a).norm();
  if ((b - a).norm() == 0.0) return 0;
  const Vector3d u = (b - a).normalized();
  auto off_line = [&](const Vector3d& x) { return ((x - a) - u * u.dot(x - a)).norm(); };
  const Vector3d c = farthest(off_line);
  if (off_line(c) <= tol) return 1;
  const Vector3d n = u.cross(c - a).normalized();
  auto off_plane = [&](const Vector3d& x) { return std::abs(n.dot(x - a)); };
  return off_plane(farthest(off_plane)) <= tol ? 2 : 3;
}

// For a solid part: the first vertex strictly inside the hull of the part (on no supporting plane
// through three of its vertices, within 1e-6 of the part's size), if any. O(n^4), n <= 128.
std::optional<std::size_t> inner_vertex(const std::vector<Vector3d>& v) {
  const double tol = 1e-6 * bounding_diagonal(v);
  std::vector<bool> on_hull(v.size(), false);
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      for (std::size_t k = j + 1; k < v.size(); ++k) {
        const Vector3d n = (v[j] - v[i]).cross(v[k] - v[i]);
        if (n.norm() <= tol * tol) continue;
        const Vector3d u = n.normalized();
        std::size_t above = 0, below = 0;
        for (const Vector3d& x : v) above += u.dot(x - v[i]) > tol, below += u.dot(x - v[i]) < -tol;
        if (above > 0 && below > 0) continue;
        for (std::size_t m = 0; m < v.size(); ++m)
          if (std::abs(u.dot(v[m] - v[i])) <= tol) on_hull[m] = true;
      }
  for (std::size_t m = 0; m < v.size(); ++m)
    if (!on_hull[m]) return m;
  return std::nullopt;
}

// The first face whose plane has vertices of the part strictly on both sides (within 1e-6 of the
// part's size): on a closed convex surface every face's plane supports the part.
std::optional<std::size_t> folded_face(const RawPart& p) {
  const double tol = 1e-6 * bounding_diagonal(p.v);
  for (std::size_t t = 0; t < p.tris.size(); ++t) {
    const Vector3d& a = p.v[p.tris[t][0]];
    const Vector3d n = (p.v[p.tris[t][1]] - a).cross(p.v[p.tris[t][2]] - a);
    if (n.norm() <= tol * tol) continue;  // a sliver: no plane of its own
    const Vector3d u = n.normalized();
    bool above = false, below = false;
    for (const Vector3d& x : p.v) above |= u.dot(x - a) > tol, below |= u.dot(x - a) < -tol;
    if (above && below) return t;
  }
  return std::nullopt;
}

const char* dimension_words(int dim) {
  return dim == 0 ? "all at one point" : dim == 1 ? "on one line" : "in one plane";
}

void check_part(const RawPart& p, double radius, const Source& src) {
  const std::string& part = p.label;
  if (p.v.size() > kMaxCoreVertices)
    src.fail(p.at, part + " has " + std::to_string(p.v.size()) + " distinct vertices, more than the " +
                       std::to_string(kMaxCoreVertices) + " a core may have",
             "keep the corners of the part's convex hull only, or split it into several parts");
  const int dim = affine_dimension(p.v);
  if (dim < 3 && radius <= 0.0)
    src.fail(p.at, part + " spans no volume: its " + std::to_string(p.v.size()) + " vertices are " + dimension_words(dim),
             "give the part 4 or more vertices not in one plane, or give the shape a dilation radius above 0 "
             "(then the part is a sphere, a capsule or a plate)");
  if (dim < 3) return;
  const char* split = "split the part into convex parts (one `o` or `g` group, or one STL solid, each)";
  if (const std::optional<std::size_t> t = folded_face(p))
    src.fail(p.tri_at[*t], "a face of " + part + " has vertices of the part on both sides of its plane: the part is not convex",
             split);
  if (const std::optional<std::size_t> m = inner_vertex(p.v))
    src.fail(p.v_at[*m], "a vertex of " + part + " lies inside the part's convex hull: the part is not convex", split);
}

ShapeSpec finish(std::vector<RawPart> parts, double radius, const Source& src) {
  std::erase_if(parts, [](const RawPart& p) { return p.v.empty(); });
  if (parts.empty()) src.fail(0, "the file holds no vertices", "give each convex part its vertices");
  if (parts.size() > kMaxShapeParts)
    src.fail(0, "the file holds " + std::to_string(parts.size()) + " parts, more than the " +
                    std::to_string(kMaxShapeParts) + " a shape may have",
             "merge or drop parts");
  ShapeSpec shape{{}, radius};
  for (const RawPart& p : parts) {
    check_part(p, radius, src);
    shape.parts.push_back(p.v);
  }
  return shape;
}

void check_radius(double radius, const Source& src) {
  if (!std::isfinite(radius) || radius < 0.0)
    src.fail(0, "the dilation radius " + short_number(radius) + " is not finite and >= 0", "give a radius of 0 or more (m)");
}

std::string read_whole(const std::filesystem::path& file, const Source& src) {
  std::string data;
  FileProblem why;
  if (!read_regular_file(file, kMaxShapeFileBytes, data, why)) src.fail(0, "shape file: " + why.problem, why.fix);
  return data;
}

// ---- Text lines and numbers -------------------------------------------------------------------------

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> tokens(std::string_view s) {
  std::vector<std::string_view> t;
  while (!(s = trim(s)).empty()) {
    const std::size_t end = std::min(s.find(' '), s.find('\t'));
    t.push_back(s.substr(0, end));
    s.remove_prefix(end == std::string_view::npos ? s.size() : end);
  }
  return t;
}

// Reads a text line by line, counting lines from 1. A line is at most 64 KiB (a face of the most
// triangles a part may have fits), so no line's tokens take much memory.
struct Lines {
  const Source& src;
  std::string_view rest;
  std::size_t number = 0;
  bool next(std::string_view& line) {
    if (rest.empty()) return false;
    const std::size_t nl = rest.find('\n');
    if (std::min(nl, rest.size()) > 65536)
      src.fail(number + 1, "the line is longer than 65536 characters", "check that this is a text OBJ or STL file");
    line = trim(rest.substr(0, nl));
    rest.remove_prefix(nl == std::string_view::npos ? rest.size() : nl + 1);
    ++number;
    return true;
  }
  // The next line that is not blank, or false at the end.
  bool next_filled(std::string_view& line) {
    while (next(line))
      if (!line.empty()) return true;
    return false;
  }
};

// A finite number, or the reason it is not.
std::optional<double> finite_number(std::string_view s) {
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

Vector3d point(std::span<const std::string_view> t, const Source& src, std::size_t line, const char* what) {
  Vector3d x;
  for (int a = 0; a < 3; ++a) {
    const std::optional<double> v = finite_number(t[a]);
    if (!v) src.fail(line, std::string(what) + " has " + gf::quoted(t[a]) + ", not a finite number",
                     "write each coordinate as a decimal number such as 0.015 or 1.5e-2");
    x[a] = *v;
  }
  return x;
}

// ---- OBJ --------------------------------------------------------------------------------------------

// An OBJ group: the vertices declared after its statement, those its faces use (in order, once),
// and its faces fanned into triangles of the file's vertices.
struct ObjGroup {
  RawPart declared;
  std::vector<std::uint32_t> used;
  std::set<std::uint32_t> used_set;
  std::vector<Triangle> tris;
  std::vector<std::size_t> tri_at;
};

struct ObjReader {
  const Source& src;
  std::vector<Vector3d> vertices;
  std::vector<std::size_t> vertex_line;
  std::vector<ObjGroup> groups;
  std::map<std::string, std::size_t, std::less<>> by_name;
  std::size_t current = 0;
  bool faces = false;

  explicit ObjReader(const Source& s) : src(s) {
    groups.emplace_back();
    groups.back().declared.label = "part '(unnamed)'";
    groups.back().declared.at = 1;
  }

  void group(std::string_view name, std::size_t line) {
    const std::string key = name.empty() ? "(unnamed)" : std::string(name);
    if (const auto it = by_name.find(key); it != by_name.end()) {
      current = it->second;
      return;
    }
    if (groups.size() >= 4 * kMaxShapeParts)
      src.fail(line, "more than " + std::to_string(4 * kMaxShapeParts) + " groups", "merge groups into fewer parts");
    groups.emplace_back();
    groups.back().declared.label = "part " + gf::quoted(key);
    groups.back().declared.at = line;
    current = by_name[key] = groups.size() - 1;
  }

  void vertex(std::span<const std::string_view> t, std::size_t line) {
    if (t.size() != 4 && t.size() != 5 && t.size() != 7)
      src.fail(line, "a vertex line has " + std::to_string(t.size() - 1) + " numbers",
               "write `v x y z` (optionally followed by w, or by r g b)");
    for (std::size_t i = 4; i < t.size(); ++i)
      if (!finite_number(t[i]))
        src.fail(line, "the vertex has " + gf::quoted(t[i]) + ", not a finite number", "write w or r g b as decimal numbers");
    const Vector3d x = point(t.subspan(1, 3), src, line, "the vertex");
    if (vertices.size() >= kMaxFileVertices)
      src.fail(line, "more than " + std::to_string(kMaxFileVertices) + " vertices",
               "a shape has at most " + std::to_string(kMaxShapeParts) + " parts of " +
                   std::to_string(kMaxCoreVertices) + " vertices: keep each part's hull corners only");
    vertices.push_back(x), vertex_line.push_back(line);
    RawPart& p = groups[current].declared;
    p.v.push_back(x), p.v_at.push_back(line);
  }

  std::uint32_t face_index(std::string_view ref, std::size_t line) const {
    const std::string_view index = ref.substr(0, ref.find('/'));
    long long i = 0;
    const auto [end, ec] = std::from_chars(index.data(), index.data() + index.size(), i);
    const long long n = static_cast<long long>(vertices.size());
    if (ec != std::errc() || end != index.data() + index.size() || i == 0 || i > n || i < -n)
      src.fail(line, "the face's vertex " + gf::quoted(ref) + " is not the index of a vertex read before it (1 to " +
                         std::to_string(n) + ", or -1 to -" + std::to_string(n) + " counting back)",
               "give each face corner as i, i/t, i//n or i/t/n with i a vertex read above");
    return static_cast<std::uint32_t>(i > 0 ? i - 1 : n + i);
  }

  void use(ObjGroup& g, std::uint32_t k, std::size_t line) const {
    if (!g.used_set.insert(k).second) return;
    if (g.used.size() >= kMaxCoreVertices)
      src.fail(line, "the faces of " + g.declared.label + " use more than " +
                         std::to_string(kMaxCoreVertices) + " vertices",
               "keep the corners of the part's convex hull only, or split it into several parts");
    g.used.push_back(k);
  }

  void face(std::span<const std::string_view> t, std::size_t line) {
    if (t.size() < 4) src.fail(line, "a face has fewer than 3 corners", "give each face 3 or more vertex indices");
    ObjGroup& g = groups[current];
    if (g.tris.size() + t.size() - 3 > kMaxPartTriangles)
      src.fail(line, g.declared.label + " has more than " + std::to_string(kMaxPartTriangles) +
                         " face triangles",
               "remove repeated faces, or split the part into several parts");
    std::vector<std::uint32_t> k;
    for (std::size_t i = 1; i < t.size(); ++i) k.push_back(face_index(t[i], line)), use(g, k.back(), line);
    for (std::size_t i = 1; i + 1 < k.size(); ++i) g.tris.push_back({k[0], k[i], k[i + 1]}), g.tri_at.push_back(line);
    faces = true;
  }

  void statement(std::string_view line_text, std::size_t line) {
    if (line_text.empty() || line_text.front() == '#') return;
    const std::vector<std::string_view> t = tokens(line_text);
    const std::string_view key = t.front();
    if (key == "v") return vertex(t, line);
    if (key == "f") return face(t, line);
    if (key == "o" || key == "g") return group(trim(line_text.substr(1)), line);
    static const std::set<std::string_view> ignored{"vn", "vt", "vp", "s", "l", "p", "usemtl", "mtllib"};
    if (ignored.contains(key)) return;
    src.fail(line, "unknown statement " + gf::quoted(key),
             "an OBJ shape has `v` vertices grouped by `o` or `g` (and optionally `f` faces); remove the line");
  }

  // A part of the vertices the group's faces use, each once, where they were declared.
  RawPart used_part(const ObjGroup& g) const {
    RawPart p{g.declared.label, g.declared.at, {}, {}, {}, g.tri_at};
    std::map<std::uint32_t, std::uint32_t> local;
    for (const std::uint32_t k : g.used) {
      local.emplace(k, static_cast<std::uint32_t>(p.v.size()));
      p.v.push_back(vertices[k]), p.v_at.push_back(vertex_line[k]);
    }
    for (const Triangle& t : g.tris) p.tris.push_back({local.at(t[0]), local.at(t[1]), local.at(t[2])});
    return p;
  }

  std::vector<RawPart> parts() const {
    std::vector<RawPart> out;
    for (const ObjGroup& g : groups) out.push_back(faces ? used_part(g) : g.declared);
    return out;
  }
};

// The coordinates as a key: equal points alike, -0 and 0 too.
std::array<double, 3> key_of(const Vector3d& x) { return {x.x() + 0.0, x.y() + 0.0, x.z() + 0.0}; }

// Exact duplicates dropped, the first kept, the triangles renumbered.
RawPart distinct(const RawPart& p) {
  RawPart out{p.label, p.at, {}, {}, {}, p.tri_at};
  std::map<std::array<double, 3>, std::uint32_t> seen;
  std::vector<std::uint32_t> to(p.v.size());
  for (std::size_t i = 0; i < p.v.size(); ++i) {
    const auto [it, fresh] = seen.emplace(key_of(p.v[i]), static_cast<std::uint32_t>(out.v.size()));
    if (fresh) out.v.push_back(p.v[i]), out.v_at.push_back(p.v_at[i]);
    to[i] = it->second;
  }
  for (const Triangle& t : p.tris) out.tris.push_back({to[t[0]], to[t[1]], to[t[2]]});
  return out;
}

// ---- STL --------------------------------------------------------------------------------------------

// Triangles' corners as distinct vertices of their solid (vertices of different solids never merge),
// and each solid's connected components as parts.
struct Mesh {
  const Source& src;
  std::size_t solid = 0;                // the solid being read, from 0
  std::vector<std::string> solid_names;  // for the parts' labels
  std::vector<Vector3d> vertices;
  std::vector<std::size_t> vertex_at, vertex_solid;
  std::map<std::pair<std::size_t, std::array<double, 3>>, std::uint32_t> index;
  std::vector<std::uint32_t> parent;  // union-find over vertices
  std::vector<Triangle> tris;
  std::vector<std::size_t> tri_at;

  explicit Mesh(const Source& s) : src(s) {}

  std::uint32_t root(std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }

  std::uint32_t add(const Vector3d& x, std::size_t at) {
    const auto key = std::make_pair(solid, key_of(x));
    if (const auto it = index.find(key); it != index.end()) return it->second;
    if (vertices.size() >= kMaxFileVertices)
      src.fail(at, "more than " + std::to_string(kMaxFileVertices) + " distinct vertices",
               "a shape has at most " + std::to_string(kMaxShapeParts) + " parts of " +
                   std::to_string(kMaxCoreVertices) + " vertices: keep each part's hull corners only");
    const auto i = static_cast<std::uint32_t>(vertices.size());
    vertices.push_back(x), vertex_at.push_back(at), vertex_solid.push_back(solid), parent.push_back(i);
    index.emplace(key, i);
    return i;
  }

  void triangle(const std::array<Vector3d, 3>& t, const std::array<std::size_t, 3>& at) {
    if (tris.size() >= kMaxFileTriangles)
      src.fail(at[0], "more than " + std::to_string(kMaxFileTriangles) + " triangles",
               "a convex part of n vertices needs at most 2 n - 4 triangles: remove repeated triangles");
    const Triangle k{add(t[0], at[0]), add(t[1], at[1]), add(t[2], at[2])};
    parent[root(k[1])] = root(k[0]);
    parent[root(k[2])] = root(k[0]);
    tris.push_back(k), tri_at.push_back(at[0]);
  }

  // "piece k of solid 'name'" (a binary file's solid has no name).
  std::string label(std::size_t s, std::size_t piece) const {
    const std::string name = s < solid_names.size() ? solid_names[s] : "";
    return "piece " + std::to_string(piece) + (name.empty() ? "" : " of solid " + gf::quoted(name));
  }

  // Components in the order their first vertices were read, vertices in the order read.
  std::vector<RawPart> parts() {
    std::map<std::uint32_t, std::size_t> part_of;  // root -> part
    std::vector<std::uint32_t> local(vertices.size());
    std::vector<RawPart> out;
    std::vector<std::size_t> pieces(solid_names.size() + 1, 0);  // per solid so far
    for (std::uint32_t i = 0; i < vertices.size(); ++i) {
      const auto [it, fresh] = part_of.emplace(root(i), out.size());
      if (fresh) out.push_back({label(vertex_solid[i], ++pieces[vertex_solid[i]]), vertex_at[i], {}, {}, {}, {}});
      RawPart& p = out[it->second];
      local[i] = static_cast<std::uint32_t>(p.v.size());
      p.v.push_back(vertices[i]), p.v_at.push_back(vertex_at[i]);
    }
    for (std::size_t t = 0; t < tris.size(); ++t) {
      RawPart& p = out[part_of.at(root(tris[t][0]))];
      if (p.tris.size() >= kMaxPartTriangles)
        src.fail(tri_at[t], p.label + " has more than " + std::to_string(kMaxPartTriangles) +
                                " triangles",
                 "remove repeated triangles, or split the part into several solids");
      p.tris.push_back({local[tris[t][0]], local[tris[t][1]], local[tris[t][2]]}), p.tri_at.push_back(tri_at[t]);
    }
    return out;
  }
};

// The ASCII grammar: solid { facet normal n n n / outer loop / vertex x3 / endloop / endfacet } endsolid.
struct AsciiStl {
  const Source& src;
  Mesh& mesh;
  Lines lines;
  std::size_t solid_line = 0;

  // The next line: `keyword` and `words` words in all (the form's), or an error.
  std::vector<std::string_view> expect(const char* keyword, std::size_t words, const char* form, const char* fix) {
    std::string_view text;
    if (!lines.next_filled(text))
      src.fail(lines.number, std::string("the file ends where `") + form + "` was expected (in the solid opened on line " +
                                 std::to_string(solid_line) + ")",
               fix);
    std::vector<std::string_view> t = tokens(text);
    if (lower(t.front()) != keyword || t.size() != words)
      src.fail(lines.number, gf::quoted(text) + " where `" + form + "` was expected", fix);
    return t;
  }

  void facet(const std::vector<std::string_view>& head) {
    if (head.size() != 5 || lower(head[1]) != "normal")
      src.fail(lines.number, "a facet line is " + gf::quoted(tokens_text(head)), "write `facet normal nx ny nz`");
    point(std::span(head).subspan(2, 3), src, lines.number, "the facet's normal");
    const std::vector<std::string_view> loop = expect("outer", 2, "outer loop", "write `outer loop` after `facet normal ...`");
    if (lower(loop[1]) != "loop") src.fail(lines.number, "`outer` without `loop`", "write `outer loop`");
    std::array<Vector3d, 3> corner;
    std::array<std::size_t, 3> at{};
    for (int k = 0; k < 3; ++k) {
      const std::vector<std::string_view> t = expect("vertex", 4, "vertex x y z", "write three `vertex x y z` lines in each loop");
      corner[k] = point(std::span(t).subspan(1, 3), src, lines.number, "the vertex");
      at[k] = lines.number;
    }
    expect("endloop", 1, "endloop", "end each loop with `endloop` after its three vertices");
    expect("endfacet", 1, "endfacet", "end each facet with `endfacet`");
    mesh.triangle(corner, at);
  }

  static std::string tokens_text(const std::vector<std::string_view>& t) {
    std::string s;
    for (const std::string_view w : t) s += (s.empty() ? "" : " ") + std::string(w);
    return s;
  }

  void solid() {
    for (;;) {
      const std::vector<std::string_view> t = expect_either();
      if (lower(t.front()) == "endsolid") return;
      facet(t);
    }
  }

  std::vector<std::string_view> expect_either() {
    std::string_view text;
    if (!lines.next_filled(text))
      src.fail(lines.number, "the file ends inside the solid opened on line " + std::to_string(solid_line),
               "end the solid with `endsolid`");
    std::vector<std::string_view> t = tokens(text);
    const std::string k = lower(t.front());
    if (k != "facet" && k != "endsolid")
      src.fail(lines.number, gf::quoted(text) + " where `facet` or `endsolid` was expected",
               "write facets as `facet normal ...` ... `endfacet` and end the solid with `endsolid`");
    return t;
  }

  void read() {
    std::string_view text;
    while (lines.next_filled(text)) {
      if (lower(tokens(text).front()) != "solid")
        src.fail(lines.number, gf::quoted(text) + " where `solid` was expected", "begin each solid with `solid [name]`");
      solid_line = lines.number;
      mesh.solid = mesh.solid_names.size();
      mesh.solid_names.emplace_back(trim(text.substr(5)));
      solid();
    }
  }
};

float read_float(const char* p) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, p, 4);
  if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
  return std::bit_cast<float>(bits);
}

std::uint32_t binary_count(std::string_view b) {
  std::uint32_t n = 0;
  std::memcpy(&n, b.data() + 80, 4);
  if constexpr (std::endian::native == std::endian::big) n = __builtin_bswap32(n);
  return n;
}

bool is_binary_stl(std::string_view b) {
  return b.size() >= 84 && b.size() - 84 == std::uint64_t{50} * binary_count(b);
}

// 80 bytes of header, the triangle count, then per triangle a normal, three corners (12 floats) and
// 2 bytes of attributes.
void read_binary_stl(std::string_view b, Mesh& mesh, const Source& src) {
  const std::uint32_t n = binary_count(b);
  if (n > kMaxFileTriangles)
    src.fail(0, "the file holds " + std::to_string(n) + " triangles, more than the " + std::to_string(kMaxFileTriangles) +
                    " a shape may have",
             "a convex part of n vertices needs at most 2 n - 4 triangles: remove repeated triangles");
  for (std::uint32_t t = 0; t < n; ++t) {
    const char* p = b.data() + 84 + std::size_t{50} * t;
    std::array<Vector3d, 3> corner;
    for (int k = 0; k < 4; ++k) {
      const Vector3d x(read_float(p + 12 * k), read_float(p + 12 * k + 4), read_float(p + 12 * k + 8));
      if (!x.allFinite())
        src.fail(t + 1, std::string(k == 0 ? "the normal" : "a corner") + " is not finite",
                 "export the mesh again: every coordinate must be a finite number");
      if (k > 0) corner[k - 1] = x;
    }
    mesh.triangle(corner, {t + 1, t + 1, t + 1});
  }
}

}  // namespace

ShapeSpec parse_obj_shape(std::string_view text, const std::string& name, double radius) {
  const Source src{name, false};
  check_radius(radius, src);
  ObjReader obj(src);
  Lines lines{src, text};
  std::string_view line;
  while (lines.next(line)) obj.statement(line, lines.number);
  std::vector<RawPart> parts;
  for (const RawPart& p : obj.parts()) parts.push_back(distinct(p));
  return finish(std::move(parts), radius, src);
}

ShapeSpec parse_stl_shape(std::string_view bytes, const std::string& name, double radius) {
  const bool binary = is_binary_stl(bytes);
  const Source src{name, binary};
  check_radius(radius, src);
  Mesh mesh(src);
  if (binary) {
    read_binary_stl(bytes, mesh, src);
  } else {
    if (!trim(bytes.substr(0, 512)).starts_with("solid"))
      src.fail(0, "neither an ASCII STL (which starts with `solid`) nor a binary one (84 + 50 n bytes for its n triangles)",
               "export the mesh again as STL");
    AsciiStl{src, mesh, Lines{src, bytes}}.read();
  }
  return finish(mesh.parts(), radius, src);
}

ShapeSpec read_obj_shape(const std::filesystem::path& file, double radius) {
  return parse_obj_shape(read_whole(file, Source{file.string()}), file.string(), radius);
}

ShapeSpec read_stl_shape(const std::filesystem::path& file, double radius) {
  return parse_stl_shape(read_whole(file, Source{file.string()}), file.string(), radius);
}

ShapeSpec read_shape_file(const std::filesystem::path& file, double radius) {
  const std::string ext = lower(file.extension().string());
  if (ext == ".obj") return read_obj_shape(file, radius);
  if (ext == ".stl") return read_stl_shape(file, radius);
  Source{file.string()}.fail(0, "the shape file's extension is " + gf::quoted(file.extension().string()) + ", not .obj or .stl",
                             "give a Wavefront OBJ (.obj) or an STL (.stl) file");
}

}  // namespace gf
