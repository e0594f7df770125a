#include "systems/walls/triangle_mesh.hpp"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numbers>
#include <numeric>

#include "engine/read_file.hpp"
#include "engine/scene.hpp"
#include "engine/user_text.hpp"

namespace gf {

namespace {

[[noreturn]] void fail(const std::string& where, const std::string& problem, const std::string& fix) {
  throw MeshError(where + ": " + problem + ". Fix: " + fix);
}

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
double norm(const Vec3d& v) { return std::sqrt(dot(v, v)); }

// ---- ASCII STL ----------------------------------------------------------------------------------------

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

bool same_word(std::string_view a, std::string_view keyword) {
  if (a.size() != keyword.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != keyword[i]) return false;
  return true;
}

// Splits a line into at most 8 words (an STL line has at most 5).
struct Words {
  std::array<std::string_view, 8> w{};
  std::size_t n = 0;
  explicit Words(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && n < w.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      if (i >= line.size()) break;
      const std::size_t b = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      w[n++] = line.substr(b, i - b);
    }
  }
};

struct AsciiReader {
  std::string_view text;
  const std::string& name;
  TriangleSoup& out;
  std::size_t pos = 0, line = 0, solid_line = 0;

  std::string at(std::size_t l) const { return name + ":" + std::to_string(l); }

  // The next line with a word on it; false at the end of the text.
  bool next(Words& words, std::string_view& raw) {
    while (pos < text.size()) {
      const std::size_t end = std::min(text.find('\n', pos), text.size());
      raw = trim(text.substr(pos, end - pos));
      pos = end + 1;
      ++line;
      if (raw.size() > 4096)
        fail(at(line), "the line is longer than 4096 characters", "check that this is an STL file");
      if (raw.empty()) continue;
      words = Words(raw);
      return true;
    }
    return false;
  }

  Words expect(const char* keyword, std::size_t count, const char* form) {
    Words w{""};
    std::string_view raw;
    if (!next(w, raw))
      fail(at(line), std::string("the file ends where `") + form + "` was expected (in the solid opened on line " +
                         std::to_string(solid_line) + ")",
           "export the mesh again: the file is cut short");
    if (!same_word(w.w[0], keyword) || w.n != count)
      fail(at(line), quoted(raw) + " where `" + form + "` was expected",
           "write each facet as `facet normal nx ny nz`, `outer loop`, three `vertex x y z`, `endloop`, `endfacet`");
    return w;
  }

  double number(std::string_view s, const char* what) {
    std::string_view t = s;
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    double v = 0;
    const auto [p, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    if (ec != std::errc() || p != t.data() + t.size())
      fail(at(line), quoted(s) + " in " + what + " is not a number", "write coordinates as decimal numbers, e.g. 0.05");
    if (!std::isfinite(v))
      fail(at(line), std::string(what) + " holds " + quoted(s) + ", not a finite number",
           "export the mesh again: every coordinate must be finite (facet normals may be written 0 0 0)");
    return v;
  }

  void facet(const Words& head) {
    if (head.n != 5 || !same_word(head.w[1], "normal"))
      fail(at(line), "a facet line is not `facet normal nx ny nz`", "write `facet normal nx ny nz`");
    for (int k = 0; k < 3; ++k) number(head.w[2 + k], "the facet's normal");
    const std::size_t facet_line = line;
    const Words loop = expect("outer", 2, "outer loop");
    if (!same_word(loop.w[1], "loop")) fail(at(line), "`outer` without `loop`", "write `outer loop`");
    Vec3d c[3];
    for (int k = 0; k < 3; ++k) {
      const Words v = expect("vertex", 4, "vertex x y z");
      c[k] = {number(v.w[1], "the vertex"), number(v.w[2], "the vertex"), number(v.w[3], "the vertex")};
    }
    expect("endloop", 1, "endloop");
    expect("endfacet", 1, "endfacet");
    out.add(c[0], c[1], c[2], facet_line);
  }

  void read() {
    Words w{""};
    std::string_view raw;
    while (next(w, raw)) {
      if (!same_word(w.w[0], "solid"))
        fail(at(line), quoted(raw) + " where `solid` was expected", "begin each solid with `solid [name]`");
      solid_line = line;
      for (;;) {
        if (!next(w, raw))
          fail(at(line), "the file ends inside the solid opened on line " + std::to_string(solid_line),
               "end the solid with `endsolid` (or export the mesh again: the file may be cut short)");
        if (same_word(w.w[0], "endsolid")) break;
        if (!same_word(w.w[0], "facet"))
          fail(at(line), quoted(raw) + " where `facet` or `endsolid` was expected",
               "write facets as `facet normal ...` ... `endfacet` and end the solid with `endsolid`");
        facet(w);
      }
    }
  }
};

// ---- Binary STL ---------------------------------------------------------------------------------------

std::uint32_t read_u32(const char* p) {
  std::uint32_t n = 0;
  std::memcpy(&n, p, 4);
  if constexpr (std::endian::native == std::endian::big) n = __builtin_bswap32(n);
  return n;
}
float read_f32(const char* p) { return std::bit_cast<float>(read_u32(p)); }
void put_u32(std::string& s, std::uint32_t v) {
  if constexpr (std::endian::native == std::endian::big) v = __builtin_bswap32(v);
  char b[4];
  std::memcpy(b, &v, 4);
  s.append(b, 4);
}
void put_f32(std::string& s, double v) { put_u32(s, std::bit_cast<std::uint32_t>(static_cast<float>(v))); }

Vec3d unit(const Vec3d& v) { return (1.0 / norm(v)) * v; }

// Two unit vectors completing `axis` to a right-handed frame (e1 x e2 = axis).
void frame(const Vec3d& axis, Vec3d& e1, Vec3d& e2) {
  const Vec3d trial = std::abs(axis.x) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  e1 = unit(trial - dot(trial, axis) * axis);
  e2 = cross(axis, e1);
}

}  // namespace

std::string TriangleSoup::where(std::size_t t) const {
  return binary ? name + ": triangle " + std::to_string(at[t]) : name + ":" + std::to_string(at[t]);
}

TriangleSoup parse_stl(std::string_view bytes, const std::string& name) {
  TriangleSoup soup;
  soup.name = name;
  if (bytes.size() >= 84) {
    const std::uint64_t n = read_u32(bytes.data() + 80);
    const std::uint64_t want = 84 + 50 * n;
    if (bytes.size() == want) {
      soup.binary = true;
      soup.corners.reserve(3 * n);
      soup.at.reserve(n);
      for (std::uint64_t t = 0; t < n; ++t) {
        const char* p = bytes.data() + 84 + 50 * t;
        Vec3d c[4];
        for (int k = 0; k < 4; ++k)
          c[k] = {read_f32(p + 12 * k), read_f32(p + 12 * k + 4), read_f32(p + 12 * k + 8)};
        for (int k = 0; k < 4; ++k)
          if (!finite(c[k]))
            fail(name + ": triangle " + std::to_string(t + 1),
                 std::string(k == 0 ? "the facet normal" : "a corner") + " is not a finite number (NaN or infinite)",
                 "export the mesh again: every coordinate must be finite (normals may be 0 0 0)");
        soup.add(c[1], c[2], c[3], static_cast<std::size_t>(t + 1));
      }
      return soup;
    }
    const std::string_view head = trim(bytes.substr(0, 512));
    if (!(head.size() >= 5 && same_word(head.substr(0, 5), "solid"))) {
      // A count past 10^8 triangles (5 GB) is more likely text or junk than a cut binary file.
      if (bytes.size() < want && n <= 100000000)
        fail(name, "a binary STL whose header states " + std::to_string(n) + " triangles (" + std::to_string(want) +
                       " bytes) but which holds " + std::to_string(bytes.size()) + " bytes: the file is truncated",
             "copy or export the file again in full");
      fail(name, "neither an ASCII STL (which starts with `solid`) nor a binary one (84 + 50 n bytes for its n "
                 "triangles; this file has " + std::to_string(bytes.size()) + " bytes for the " + std::to_string(n) +
                     " its header states)",
           "export the mesh again as STL");
    }
  } else if (!(trim(bytes).size() >= 5 && same_word(trim(bytes).substr(0, 5), "solid"))) {
    fail(name, "the file holds " + std::to_string(bytes.size()) + " bytes: too short for a binary STL (84 bytes at least) "
                   "and not an ASCII one (which starts with `solid`)",
         "export the mesh again as STL");
  }
  AsciiReader{bytes, name, soup}.read();
  return soup;
}

TriangleSoup read_stl(const std::filesystem::path& file) {
  std::string data;
  FileProblem why;
  if (!read_regular_file(file, kMaxStlBytes, data, why)) fail(shown_path(file.string()), "mesh file: " + why.problem, why.fix);
  return parse_stl(data, shown_path(file.string()));
}

void write_stl_binary(const std::filesystem::path& file, const TriangleSoup& soup) {
  std::string s(80, '\0');
  const std::string head = "binary STL of " + soup.name;
  std::memcpy(s.data(), head.data(), std::min<std::size_t>(head.size(), 79));
  put_u32(s, static_cast<std::uint32_t>(soup.size()));
  for (std::size_t t = 0; t < soup.size(); ++t) {
    const Vec3d &a = soup.corners[3 * t], &b = soup.corners[3 * t + 1], &c = soup.corners[3 * t + 2];
    const Vec3d n = cross(b - a, c - a);
    const double len = norm(n);
    const Vec3d u = len > 0 ? (1.0 / len) * n : Vec3d{0, 0, 0};
    for (const Vec3d& v : {u, a, b, c}) put_f32(s, v.x), put_f32(s, v.y), put_f32(s, v.z);
    s.append(2, '\0');
  }
  std::ofstream f(file, std::ios::binary);
  f.write(s.data(), static_cast<std::streamsize>(s.size()));
  if (!f) throw MeshError(file.string() + ": cannot write the STL file. Fix: check the folder exists and is writable");
}

void write_stl_ascii(const std::filesystem::path& file, const TriangleSoup& soup) {
  std::ofstream f(file);
  char buf[256];
  f << "solid mesh\n";
  for (std::size_t t = 0; t < soup.size(); ++t) {
    const Vec3d &a = soup.corners[3 * t], &b = soup.corners[3 * t + 1], &c = soup.corners[3 * t + 2];
    const Vec3d n = cross(b - a, c - a);
    const double len = norm(n);
    const Vec3d u = len > 0 ? (1.0 / len) * n : Vec3d{0, 0, 0};
    std::snprintf(buf, sizeof buf, "  facet normal %.17g %.17g %.17g\n    outer loop\n", u.x, u.y, u.z);
    f << buf;
    for (const Vec3d& v : {a, b, c}) {
      std::snprintf(buf, sizeof buf, "      vertex %.17g %.17g %.17g\n", v.x, v.y, v.z);
      f << buf;
    }
    f << "    endloop\n  endfacet\n";
  }
  f << "endsolid mesh\n";
  if (!f) throw MeshError(file.string() + ": cannot write the STL file. Fix: check the folder exists and is writable");
}

// ---- Primitives ---------------------------------------------------------------------------------------

// Each primitive computes every vertex once and then refers to it, so that triangles sharing a vertex
// share its exact coordinates (the same expression evaluated at two places may round differently
// where the compiler contracts it into fused multiply-adds).
TriangleSoup plate_triangles(const Vec3d& center, const Vec3d& normal, const Vec3d& u_in, double half_u,
                             double half_v, int cells_u, int cells_v) {
  const Vec3d n = unit(normal);
  const Vec3d u = unit(u_in - dot(u_in, n) * n);
  const Vec3d v = cross(n, u);
  TriangleSoup s;
  s.name = "plate";
  std::vector<Vec3d> grid;
  for (int j = 0; j <= cells_v; ++j)
    for (int i = 0; i <= cells_u; ++i) {
      const double a = -half_u + 2.0 * half_u * i / cells_u, b = -half_v + 2.0 * half_v * j / cells_v;
      grid.push_back(center + a * u + b * v);
    }
  auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(j * (cells_u + 1) + i)]; };
  for (int j = 0; j < cells_v; ++j)
    for (int i = 0; i < cells_u; ++i) {
      s.add(at(i, j), at(i + 1, j), at(i + 1, j + 1), s.size() + 1);
      s.add(at(i, j), at(i + 1, j + 1), at(i, j + 1), s.size() + 1);
    }
  return s;
}

TriangleSoup annulus_triangles(const Vec3d& center, const Vec3d& axis, double inner, double outer, int segments) {
  Vec3d e1, e2;
  const Vec3d a = unit(axis);
  frame(a, e1, e2);
  TriangleSoup s;
  s.name = "annulus";
  std::vector<Vec3d> in, out;
  for (int k = 0; k < segments; ++k) {
    const double th = 2.0 * std::numbers::pi * k / segments;
    in.push_back(center + (inner * std::cos(th)) * e1 + (inner * std::sin(th)) * e2);
    out.push_back(center + (outer * std::cos(th)) * e1 + (outer * std::sin(th)) * e2);
  }
  for (int k = 0; k < segments; ++k) {
    const auto i0 = static_cast<std::size_t>(k), i1 = static_cast<std::size_t>((k + 1) % segments);
    if (inner <= 0.0) {
      s.add(center, out[i0], out[i1], s.size() + 1);
      continue;
    }
    s.add(in[i0], out[i0], out[i1], s.size() + 1);
    s.add(in[i0], out[i1], in[i1], s.size() + 1);
  }
  return s;
}

TriangleSoup cylinder_triangles(const Vec3d& center, const Vec3d& axis, double radius, double length, int segments,
                                int rings) {
  Vec3d e1, e2;
  const Vec3d a = unit(axis);
  frame(a, e1, e2);
  TriangleSoup s;
  s.name = "cylinder";
  std::vector<Vec3d> grid;
  for (int j = 0; j <= rings; ++j)
    for (int k = 0; k < segments; ++k) {
      const double th = 2.0 * std::numbers::pi * k / segments;
      const double z = -0.5 * length + length * j / rings;
      grid.push_back(center + z * a + (radius * std::cos(th)) * e1 + (radius * std::sin(th)) * e2);
    }
  auto at = [&](int k, int j) { return grid[static_cast<std::size_t>(j * segments + k % segments)]; };
  for (int j = 0; j < rings; ++j)
    for (int k = 0; k < segments; ++k) {
      s.add(at(k, j), at(k + 1, j), at(k + 1, j + 1), s.size() + 1);
      s.add(at(k, j), at(k + 1, j + 1), at(k, j + 1), s.size() + 1);
    }
  return s;
}

void transform_soup(TriangleSoup& soup, double scale, const Vec3d& translate) {
  for (Vec3d& c : soup.corners) c = translate + scale * c;
}

// ---- Geometry -----------------------------------------------------------------------------------------

namespace {

void require_usable(const TriangleSoup& soup) {
  const std::size_t nt = soup.size();
  if (nt == 0)
    fail(soup.name, "the mesh holds no triangles", "give a mesh with at least one facet (an empty solid is not a wall)");
  if (nt > (std::size_t{1} << 30))
    fail(soup.name, "the mesh holds " + std::to_string(nt) + " triangles, more than 2^30", "decimate the mesh");
  for (std::size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k)
      if (!finite(soup.corners[3 * t + static_cast<std::size_t>(k)]))
        fail(soup.where(t), "a corner is not a finite number", "check scale and translate, and the file's numbers");
}

// Weld: corners sorted by coordinates, equal ones one vertex; the vertex of each corner.
std::vector<std::uint32_t> weld(const TriangleSoup& soup, TriangleMesh& m) {
  std::vector<std::uint32_t> order(soup.corners.size());
  std::iota(order.begin(), order.end(), 0u);
  auto less = [&](std::uint32_t i, std::uint32_t j) {
    const Vec3d &a = soup.corners[i], &b = soup.corners[j];
    if (a.x != b.x) return a.x < b.x;
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
  };
  std::sort(order.begin(), order.end(), less);
  std::vector<std::uint32_t> vid(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    if (k == 0 || less(order[k - 1], order[k])) m.vertex.push_back(soup.corners[order[k]]);
    vid[order[k]] = static_cast<std::uint32_t>(m.vertex.size() - 1);
  }
  return vid;
}

// Triangle t's normal, centre, bounding radius and outward edge normals; a degenerate one refused.
void triangle_geometry(const TriangleSoup& soup, std::size_t t, TriangleMesh& m) {
  const Vec3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
  const Vec3d n = cross(b - a, c - a);
  const double longest2 = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
  const double n_len = norm(n);
  if (!(n_len > 1e-12 * longest2))
    fail(soup.where(t),
         longest2 == 0.0 ? std::string("the triangle's three corners coincide")
                         : std::string("the triangle is degenerate (its corners are collinear or two coincide)"),
         "repair the mesh (remove zero-area facets, e.g. with MeshLab's \"Remove Zero Area Faces\") and export it "
         "again");
  m.normal[t] = (1.0 / n_len) * n;
  m.centre[t] = (1.0 / 3.0) * (a + b + c);
  m.bound[t] = std::sqrt(std::max({dot(a - m.centre[t], a - m.centre[t]), dot(b - m.centre[t], b - m.centre[t]),
                                   dot(c - m.centre[t], c - m.centre[t])}));
  for (int k = 0; k < 3; ++k) {
    const Vec3d p0 = m.corner(t, k), p1 = m.corner(t, (k + 1) % 3), opp = m.corner(t, (k + 2) % 3);
    const Vec3d e = p1 - p0;
    m.shortest_edge = std::min(m.shortest_edge, norm(e));
    Vec3d out = unit(cross(e, m.normal[t]));
    if (dot(out, opp - p0) > 0) out = -out;
    m.edge_out[t][static_cast<std::size_t>(k)] = out;
  }
}

// Edges: the triangles' sides sorted by their vertex pair; the key (vertex pair) of each edge.
std::vector<std::uint64_t> build_edges(TriangleMesh& m) {
  struct Side {
    std::uint64_t key;
    std::uint32_t t;
    std::uint32_t k;
  };
  const std::size_t nt = m.tri.size();
  std::vector<Side> sides;
  sides.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
    for (std::uint32_t k = 0; k < 3; ++k) {
      const std::uint64_t a = m.tri[t][k], b = m.tri[t][(k + 1) % 3];
      sides.push_back({std::min(a, b) << 32 | std::max(a, b), static_cast<std::uint32_t>(t), k});
    }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.key != y.key ? x.key < y.key : (x.t != y.t ? x.t < y.t : x.k < y.k);
  });
  std::vector<std::uint64_t> edge_key;
  for (std::size_t s = 0; s < sides.size(); ++s) {
    if (s == 0 || sides[s].key != sides[s - 1].key) {
      m.edge_start.push_back(static_cast<std::uint32_t>(s));
      edge_key.push_back(sides[s].key);
    }
    m.edge_tri.push_back(sides[s].t);
    m.edge_of[sides[s].t][sides[s].k] = static_cast<std::uint32_t>(edge_key.size() - 1);
  }
  m.edge_start.push_back(static_cast<std::uint32_t>(sides.size()));
  return edge_key;
}

// Vertex neighbours from the edges.
void build_vertex_neighbours(const std::vector<std::uint64_t>& edge_key, TriangleMesh& m) {
  const std::size_t nv = m.vertex.size();
  m.vertex_start.assign(nv + 1, 0);
  for (const std::uint64_t k : edge_key) ++m.vertex_start[(k >> 32) + 1], ++m.vertex_start[(k & 0xffffffffu) + 1];
  for (std::size_t v = 0; v < nv; ++v) m.vertex_start[v + 1] += m.vertex_start[v];
  m.vertex_nbr.resize(m.vertex_start[nv]);
  std::vector<std::uint32_t> fill(m.vertex_start.begin(), m.vertex_start.end() - 1);
  for (const std::uint64_t k : edge_key) {
    const auto a = static_cast<std::uint32_t>(k >> 32), b = static_cast<std::uint32_t>(k & 0xffffffffu);
    m.vertex_nbr[fill[a]++] = b;
    m.vertex_nbr[fill[b]++] = a;
  }
}

// Flat regions: union-find through edges of two parallel triangles.
void build_flat_regions(TriangleMesh& m) {
  const std::size_t nt = m.tri.size();
  std::vector<std::uint32_t> parent(nt);
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t e = 0; e + 1 < m.edge_start.size(); ++e) {
    if (m.edge_start[e + 1] - m.edge_start[e] != 2) continue;
    const std::uint32_t a = m.edge_tri[m.edge_start[e]], b = m.edge_tri[m.edge_start[e] + 1];
    if (std::abs(dot(m.normal[a], m.normal[b])) >= 1.0 - 1e-9) parent[root(a)] = root(b);
  }
  m.region.resize(nt);
  std::vector<std::uint32_t> id(nt, ~0u);
  for (std::size_t t = 0; t < nt; ++t) {
    const std::uint32_t r = root(static_cast<std::uint32_t>(t));
    if (id[r] == ~0u) id[r] = m.regions++;
    m.region[t] = id[r];
  }
}

}  // namespace

TriangleMesh build_mesh(const TriangleSoup& soup) {
  require_usable(soup);
  TriangleMesh m;
  m.name = soup.name;
  const std::size_t nt = soup.size();
  const std::vector<std::uint32_t> vid = weld(soup, m);
  m.tri.resize(nt);
  m.at = soup.at;
  m.normal.resize(nt);
  m.centre.resize(nt);
  m.bound.resize(nt);
  m.edge_out.resize(nt);
  m.edge_of.resize(nt);
  m.shortest_edge = std::numeric_limits<double>::infinity();
  for (std::size_t t = 0; t < nt; ++t) {
    m.tri[t] = {vid[3 * t], vid[3 * t + 1], vid[3 * t + 2]};
    triangle_geometry(soup, t, m);
  }
  build_vertex_neighbours(build_edges(m), m);
  build_flat_regions(m);
  m.lo = m.hi = m.vertex.front();
  for (const Vec3d& v : m.vertex) {
    m.lo = {std::min(m.lo.x, v.x), std::min(m.lo.y, v.y), std::min(m.lo.z, v.z)};
    m.hi = {std::max(m.hi.x, v.x), std::max(m.hi.y, v.y), std::max(m.hi.z, v.z)};
  }
  return m;
}

TriangleGrid build_triangle_grid(const TriangleMesh& m, double reach, std::size_t max_cells) {
  TriangleGrid g;
  g.reach = reach;
  const Vec3d grow{reach, reach, reach};
  g.lo = m.lo - grow;
  const Vec3d span = (m.hi + grow) - g.lo;
  double h = reach > 0 ? reach : std::max({span.x, span.y, span.z});
  auto cells = [&](double e) {
    return static_cast<double>(std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.x / e)))) *
           static_cast<double>(std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.y / e)))) *
           static_cast<double>(std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.z / e))));
  };
  while (cells(h) > static_cast<double>(max_cells)) h *= 1.25;
  g.h = h;
  g.inv_h = 1.0 / h;
  g.nx = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.x / h)));
  g.ny = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.y / h)));
  g.nz = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(span.z / h)));
  const std::size_t nc = static_cast<std::size_t>(g.nx * g.ny * g.nz);
  const double within = reach + 0.5 * std::sqrt(3.0) * h;
  // Visits the cells listing triangle t: those of its box grown by `within` whose centre is within.
  auto visit = [&](std::size_t t, auto&& f) {
    const Vec3d a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
    const Vec3d lo{std::min({a.x, b.x, c.x}) - within, std::min({a.y, b.y, c.y}) - within,
                   std::min({a.z, b.z, c.z}) - within};
    const Vec3d hi{std::max({a.x, b.x, c.x}) + within, std::max({a.y, b.y, c.y}) + within,
                   std::max({a.z, b.z, c.z}) + within};
    auto cell_range = [&](double l, double u, double o, std::int64_t n, std::int64_t& i0, std::int64_t& i1) {
      i0 = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((l - o) * g.inv_h)), 0, n - 1);
      i1 = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((u - o) * g.inv_h)), 0, n - 1);
    };
    std::int64_t x0, x1, y0, y1, z0, z1;
    cell_range(lo.x, hi.x, g.lo.x, g.nx, x0, x1);
    cell_range(lo.y, hi.y, g.lo.y, g.ny, y0, y1);
    cell_range(lo.z, hi.z, g.lo.z, g.nz, z0, z1);
    for (std::int64_t z = z0; z <= z1; ++z)
      for (std::int64_t y = y0; y <= y1; ++y)
        for (std::int64_t x = x0; x <= x1; ++x) {
          const Vec3d centre = g.lo + Vec3d{(static_cast<double>(x) + 0.5) * h, (static_cast<double>(y) + 0.5) * h,
                                            (static_cast<double>(z) + 0.5) * h};
          const Vec3d d = closest_point_on_triangle(centre, a, b, c).q - centre;
          if (dot(d, d) <= within * within) f(static_cast<std::size_t>((z * g.ny + y) * g.nx + x));
        }
  };
  g.start.assign(nc + 1, 0);
  std::uint64_t total = 0;
  for (std::size_t t = 0; t < m.triangles(); ++t)
    visit(t, [&](std::size_t c) {
      ++g.start[c + 1];
      ++total;
    });
  if (total >= (std::uint64_t{1} << 32))
    fail(m.name, "the contact grid of the mesh would list " + std::to_string(total) + " cell entries",
         "use fewer, smaller triangles for large flat areas, or a coarser mesh");
  g.occupied.assign((nc + 63) / 64, 0);
  for (std::size_t c = 0; c < nc; ++c)
    if (g.start[c + 1] > 0) g.occupied[c >> 6] |= std::uint64_t{1} << (c & 63);
  for (std::size_t c = 0; c < nc; ++c) g.start[c + 1] += g.start[c];
  g.items.resize(total);
  std::vector<std::uint32_t> next(g.start.begin(), g.start.end() - 1);
  for (std::size_t t = 0; t < m.triangles(); ++t)
    visit(t, [&](std::size_t c) { g.items[next[c]++] = static_cast<std::uint32_t>(t); });
  return g;
}

}  // namespace gf
