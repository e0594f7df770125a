// Shapes read from files (systems/bodies/shape_files.hpp): OBJ and STL round trips to the same bits
// (floats for binary STL), malformed files as errors that name the file, line and a fix, and
// randomly mangled files that give a shape or such an error, never anything else.
#include "systems/bodies/shape_files.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

using Eigen::Vector3d;
using gf::ShapeSpec;

namespace {

// ---- Writing shape files ------------------------------------------------------------------------------

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// One `o` group per part, its vertices only.
std::string obj_text(const ShapeSpec& s) {
  std::string t = "# parts\n";
  for (std::size_t i = 0; i < s.parts.size(); ++i) {
    t += "o part" + std::to_string(i) + "\n";
    for (const Vector3d& x : s.parts[i]) t += "v " + number(x.x()) + " " + number(x.y()) + " " + number(x.z()) + "\n";
  }
  return t;
}

// The hull's triangles, outward, from the supporting planes through vertex triples.
std::vector<std::array<Vector3d, 3>> hull_triangles(const std::vector<Vector3d>& v) {
  std::vector<std::array<Vector3d, 3>> out;
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      for (std::size_t k = j + 1; k < v.size(); ++k) {
        const Vector3d n = (v[j] - v[i]).cross(v[k] - v[i]);
        if (n.norm() < 1e-12) continue;
        double lo = 0, hi = 0;
        for (const Vector3d& x : v) lo = std::min(lo, n.dot(x - v[i])), hi = std::max(hi, n.dot(x - v[i]));
        if (lo < -1e-15 && hi > 1e-15) continue;
        out.push_back(hi > 0 ? std::array<Vector3d, 3>{v[i], v[k], v[j]} : std::array<Vector3d, 3>{v[i], v[j], v[k]});
      }
  return out;
}

// One solid per part.
std::string stl_ascii(const ShapeSpec& s) {
  std::string t;
  for (std::size_t i = 0; i < s.parts.size(); ++i) {
    t += "solid part" + std::to_string(i) + "\n";
    for (const auto& tri : hull_triangles(s.parts[i])) {
      t += "  facet normal 0 0 0\n    outer loop\n";
      for (const Vector3d& x : tri) t += "      vertex " + number(x.x()) + " " + number(x.y()) + " " + number(x.z()) + "\n";
      t += "    endloop\n  endfacet\n";
    }
    t += "endsolid part" + std::to_string(i) + "\n";
  }
  return t;
}

void put_float(std::string& b, float f) {
  const auto bits = std::bit_cast<std::uint32_t>(f);
  for (int k = 0; k < 4; ++k) b += static_cast<char>(bits >> (8 * k) & 0xff);
}

// One part's hull triangles, little-endian, with `header` (80 bytes) in front.
std::string stl_binary(const std::vector<Vector3d>& part, const std::string& header) {
  const auto tris = hull_triangles(part);
  std::string b = header;
  b.resize(80, ' ');
  const auto n = static_cast<std::uint32_t>(tris.size());
  for (int k = 0; k < 4; ++k) b += static_cast<char>(n >> (8 * k) & 0xff);
  for (const auto& tri : tris) {
    for (int k = 0; k < 3; ++k) put_float(b, 0.0f);
    for (const Vector3d& x : tri)
      for (int a = 0; a < 3; ++a) put_float(b, static_cast<float>(x[a]));
    b += std::string(2, '\0');
  }
  return b;
}

// The message of the ShapeFileError that `f` throws, or "" when it throws none.
template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const gf::ShapeFileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("shape_files: OBJ round trips, vertex-only and with faces", "[bodies]") {
  // Written with 17 significant digits, read back to the same bits; a file that lists every vertex
  // first and each group's faces after gives each group the vertices its faces use.
  gf::test::TempDir dir("shape_files");
  const ShapeSpec A = gf::letter_shape('A', gf::LetterSize{}, 0.0);
  const ShapeSpec back = gf::read_shape_file(dir.write("a.obj", obj_text(A)), 0.001);
  CHECK(back.radius == 0.001);
  REQUIRE(back.parts.size() == A.parts.size());
  for (std::size_t i = 0; i < A.parts.size(); ++i) CHECK(back.parts[i] == A.parts[i]);
  const std::string faced =
      "mtllib x.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 5 5 5\nv 6 5 5\nv 5 6 5\nv 5 5 6\nvn 0 0 1\n"
      "g first\nusemtl m\ns off\nf 1//1 3//1 2//1\nf 1 2 4\nf 1 4 3\nf 2/1/1 3/1/1 4/1/1\n"
      "g second\nf -4 -2 -3\nf -4 -3 -1\nf -4 -1 -2\nf -3 -2 -1\n";
  const ShapeSpec two = gf::parse_obj_shape(faced, "faced.obj", 0.0);
  REQUIRE(two.parts.size() == 2);
  CHECK(two.parts[0] == std::vector<Vector3d>{{0, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}});
  CHECK(two.parts[1] == std::vector<Vector3d>{{5, 5, 5}, {5, 6, 5}, {6, 5, 5}, {5, 5, 6}});
}

TEST_CASE("shape_files: STL round trips, ASCII and binary", "[bodies]") {
  // ASCII: one solid per part, 17 digits, the same bits back. Binary: floats, so the vertices come
  // back as the floats nearest them; a header that begins with "solid" (as some exporters write)
  // is still binary when the size says so. Two boxes apart in one solid are two parts.
  gf::test::TempDir dir("shape_files");
  const ShapeSpec K = gf::letter_shape('K', gf::LetterSize{}, 0.002);
  const ShapeSpec back = gf::read_shape_file(dir.write("k.STL", stl_ascii(K)), 0.002);
  REQUIRE(back.parts.size() == K.parts.size());
  for (std::size_t i = 0; i < K.parts.size(); ++i) {
    auto a = K.parts[i], b = back.parts[i];
    auto less = [](const Vector3d& x, const Vector3d& y) { return std::lexicographical_compare(x.begin(), x.end(), y.begin(), y.end()); };
    std::sort(a.begin(), a.end(), less), std::sort(b.begin(), b.end(), less);
    CHECK(a == b);
  }
  const ShapeSpec cone = gf::up_down_cone_shape({0.02, 0.006, 0.03, 12}, 0.0);
  const ShapeSpec bin = gf::read_stl_shape(dir.write("c.stl", stl_binary(cone.parts[0], "solid made by a CAD program")), 0.0);
  REQUIRE(bin.parts.size() == 1);
  REQUIRE(bin.parts[0].size() == cone.parts[0].size());
  for (const Vector3d& x : cone.parts[0]) {
    const Vector3d f = x.cast<float>().cast<double>();
    CHECK(std::count(bin.parts[0].begin(), bin.parts[0].end(), f) == 1);
  }
  ShapeSpec boxes = gf::box_shape({1, 1, 1}, 0.0);
  std::string one_solid = stl_ascii(boxes);
  for (Vector3d& x : boxes.parts[0]) x.x() += 3.0;
  std::string second = stl_ascii(boxes);
  second = second.substr(second.find('\n') + 1);  // the facets only, into the first solid
  one_solid = one_solid.substr(0, one_solid.rfind("endsolid")) + second;
  CHECK(gf::parse_stl_shape(one_solid, "two.stl", 0.0).parts.size() == 2);
}

TEST_CASE("shape_files: malformed shape files are errors naming the line and a fix", "[bodies]") {
  const std::string box = "o box\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\n";
  auto obj = [](const std::string& text, double r = 0.0) {
    return error_of([&] { gf::parse_obj_shape(text, "s.obj", r); });
  };
  CHECK(obj(box) == "");
  CHECK(obj(box + "v 1 2\n").starts_with("s.obj:7: a vertex line has 2 numbers. Fix: "));
  CHECK(obj(box + "v 1 nan 2\n").starts_with("s.obj:7: the vertex has 'nan', not a finite number. Fix: "));
  CHECK(obj(box + "v 1 1e999 2\n").starts_with("s.obj:7: the vertex has '1e999'"));
  CHECK(obj(box + "v 1 2 3 x\n").starts_with("s.obj:7: the vertex has 'x'"));
  CHECK(obj(box + "f 1 2 9\n").starts_with("s.obj:7: the face's vertex '9' is not the index of a vertex"));
  CHECK(obj(box + "f 1 2\n").starts_with("s.obj:7: a face has fewer than 3 corners"));
  CHECK(obj(box + "cstype bezier\n").starts_with("s.obj:7: unknown statement 'cstype'"));
  CHECK(obj("# nothing\n").starts_with("s.obj: the file holds no vertices. Fix: "));
  // Too few points: an error at r = 0 naming the group's line, a sphere, capsule or plate at r > 0.
  const std::string three = box + "g plate\nv 0 0 5\nv 1 0 5\nv 0 1 5\n";
  CHECK(obj(three).starts_with("s.obj:7: part 'plate' spans no volume: its 3 vertices are in one plane. Fix: "));
  CHECK(obj(three, 0.1) == "");
  CHECK(obj(box + "g ball\nv 0 0 5\n", 0.1) == "");
  CHECK(obj(box + "g rod\nv 0 0 5\nv 0 0 6\nv 0 0 7\n").find("on one line") != std::string::npos);
  // Not convex: a vertex inside the hull; a face folded inward.
  CHECK(obj(box + "v 0.4 0.3 0.2\n").starts_with("s.obj:7: a vertex of part 'box' lies inside the part's convex hull"));
  std::string big = "o big\n";
  for (int i = 0; i <= 128; ++i) big += "v " + std::to_string(std::cos(i * 0.7)) + " " + std::to_string(std::sin(i * 0.7)) + " " + std::to_string(i) + "\n";
  CHECK(obj(big).starts_with("s.obj:1: part 'big' has 129 distinct vertices, more than the 128"));
  // STL.
  const std::string tet = "solid t\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n"
                          "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 0 1\nvertex 1 0 0\nendloop\nendfacet\n"
                          "facet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 0 1 0\nvertex 0 0 1\nendloop\nendfacet\n"
                          "facet normal 0 0 0\nouter loop\nvertex 1 0 0\nvertex 0 0 1\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
  auto stl = [](const std::string& text) { return error_of([&] { gf::parse_stl_shape(text, "s.stl", 0.0); }); };
  CHECK(stl(tet) == "");
  std::string bad = tet;
  bad.replace(bad.find("vertex 1 0 0"), 12, "vertex 1 0");
  CHECK(stl(bad).starts_with("s.stl:5: 'vertex 1 0' where `vertex x y z` was expected. Fix: "));
  bad = tet;
  bad.replace(bad.find("vertex 1 0 0"), 12, "vertex 1 inf 0");
  CHECK(stl(bad).starts_with("s.stl:5: the vertex has 'inf', not a finite number"));
  bad = tet;
  bad.erase(bad.find("endloop"), 8);
  CHECK(stl(bad).starts_with("s.stl:7: 'endfacet' where `endloop` was expected"));
  CHECK(stl(tet.substr(0, tet.find("endsolid"))).starts_with("s.stl:29: the file ends inside the solid opened on line 1"));
  CHECK(stl("hello\n").starts_with("s.stl: neither an ASCII STL"));
  // A folded part: a notch pushed into the tetrahedron's face, as triangles of one solid.
  std::string dent = tet;
  dent.replace(dent.rfind("vertex 1 0 0\nvertex 0 0 1\nvertex 0 1 0"), 38,
               "vertex 1 0 0\nvertex 0 0 1\nvertex 0.1 0.1 0.1\nendloop\nendfacet\nfacet normal 0 0 0\nouter loop\n"
               "vertex 0 0 1\nvertex 0 1 0\nvertex 0.1 0.1 0.1\nendloop\nendfacet\nfacet normal 0 0 0\nouter loop\n"
               "vertex 0 1 0\nvertex 1 0 0\nvertex 0.1 0.1 0.1");
  CHECK(stl(dent).find("the part is not convex") != std::string::npos);
  CHECK(stl(dent).starts_with("s.stl:"));
  // O's strokes share corners: in one solid they are one component, which is not convex.
  std::string O = stl_ascii(gf::letter_shape('O', gf::LetterSize{}, 0.0));
  for (std::size_t at; (at = O.find("endsolid", 1)) != O.rfind("endsolid");)
    O.erase(at, O.find("\n", O.find("solid", at + 8)) + 1 - at);  // "endsolid partK\nsolid partK+1\n"
  CHECK(stl(O).find("the part is not convex") != std::string::npos);
  // Binary: a non-finite corner names the triangle.
  std::string b = stl_binary(gf::box_shape({1, 1, 1}, 0.0).parts[0], "x");
  std::memcpy(b.data() + 84 + 50 * 2 + 12, "\x00\x00\xc0\x7f", 4);  // a NaN in triangle 3's first corner
  CHECK(stl(b).starts_with("s.stl: triangle 3: a corner is not finite. Fix: "));
  // Files: missing, a folder, too large, a wrong extension.
  gf::test::TempDir dir("shape_files");
  CHECK(error_of([&] { gf::read_shape_file(dir.path / "none.obj", 0.0); }).find("the file does not exist") != std::string::npos);
  CHECK(error_of([&] { gf::read_stl_shape(dir.path, 0.0); }).find("this is a folder") != std::string::npos);
  const auto huge = dir.write("huge.obj", std::string(gf::kMaxShapeFileBytes + 1, '#'));
  CHECK(error_of([&] { gf::read_obj_shape(huge, 0.0); }).find("above the") != std::string::npos);
  CHECK(error_of([&] { gf::read_shape_file(dir.write("s.txt", box), 0.0); }).find("not .obj or .stl") != std::string::npos);
  CHECK(error_of([&] { gf::parse_obj_shape(box, "s.obj", -1.0); }).find("dilation radius") != std::string::npos);
}

TEST_CASE("shape_files: mangled files give a shape or a ShapeFileError, never anything else", "[bodies]") {
  // Bytes flipped, cut or repeated at random in a valid OBJ, ASCII STL and binary STL: each read
  // returns or throws ShapeFileError (no other exception, no crash, no hang).
  const ShapeSpec T = gf::letter_shape('T', gf::LetterSize{}, 0.0);
  const std::vector<std::string> seeds{obj_text(T), stl_ascii(T), stl_binary(T.parts[0], "solid x")};
  std::mt19937 rng(12345);
  static const char kBytes[] = "0123456789 .-+eE\n/vfogsolidfacetvertexendloop\x00\xff";
  const std::string alphabet(kBytes, sizeof kBytes - 1);
  int errors = 0, shapes = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::string t = seeds[trial % seeds.size()];
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits && !t.empty(); ++e) {
      const std::size_t at = rng() % t.size();
      switch (rng() % 3) {
        case 0: t[at] = alphabet[rng() % alphabet.size()]; break;
        case 1: t.erase(at, rng() % 16); break;
        default: t.insert(at, t.substr(at, rng() % 32)); break;
      }
    }
    try {
      const ShapeSpec got = trial % 3 == 0 ? gf::parse_obj_shape(t, "m.obj", 0.0) : gf::parse_stl_shape(t, "m.stl", 0.0);
      shapes += !got.parts.empty();
    } catch (const gf::ShapeFileError&) {
      ++errors;
    }
  }
  CHECK(errors + shapes == 600);
  CHECK(errors > 0);
}
