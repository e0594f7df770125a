// Triangle-mesh geometry of mesh walls: the closest point on a triangle against brute-force sampling, the
// features it reports, STL round trips (binary and ASCII), the welded adjacency and flat regions of the
// primitives, the contact grid against brute force, and the refusal of bad files with file, place and fix.
#include "systems/walls/triangle_mesh.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>

#include "tests/test_support.hpp"

using gf::Vec3d;

namespace {

double dist(const Vec3d& a, const Vec3d& b) { return std::sqrt(gf::dot(a - b, a - b)); }

Vec3d random_vec(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return {u(rng), u(rng), u(rng)};
}

std::string message_of(auto&& f) {
  try {
    f();
  } catch (const gf::MeshError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("mesh: the closest point on a triangle is no farther than any sampled point of it", "[mesh]") {
  std::mt19937_64 rng(7);
  // Samples on a barycentric grid of step 1/n: the true minimum is at most the sampled one, and the
  // sampled one exceeds it by at most the grid's spacing (the longest edge / n).
  const int n = 120;
  int faces = 0, edges = 0, vertices = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3d a = random_vec(rng, 1.0), b = random_vec(rng, 1.0), c = random_vec(rng, 1.0);
    const Vec3d p = random_vec(rng, 2.0);
    const gf::ClosestPoint cp = gf::closest_point_on_triangle(p, a, b, c);
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        best = std::min(best, dist(p, a + u * (b - a) + v * (c - a)));
      }
    const double longest = std::max({dist(a, b), dist(b, c), dist(c, a)});
    const double d = dist(p, cp.q);
    INFO("trial " << trial << ": closest " << d << ", best sample " << best);
    REQUIRE(d <= best + 1e-12);
    REQUIRE(d >= best - longest / n);
    // The point lies on its feature.
    const Vec3d corner[3] = {a, b, c};
    if (gf::is_vertex(cp.feature)) {
      ++vertices;
      REQUIRE(dist(cp.q, corner[gf::feature_index(cp.feature)]) == 0.0);
    } else if (gf::is_edge(cp.feature)) {
      ++edges;
      const int k = gf::feature_index(cp.feature);
      const Vec3d p0 = corner[k], p1 = corner[(k + 1) % 3];
      REQUIRE(dist(p0, cp.q) + dist(cp.q, p1) == Approx(dist(p0, p1)).epsilon(1e-12));
    } else {
      ++faces;
      // Inside: the projection of p on the plane, so p - q is along the normal.
      const Vec3d nrm = gf::cross(b - a, c - a);
      const Vec3d w = p - cp.q;
      REQUIRE(std::abs(gf::dot(w, b - a)) <= 1e-12 * (1 + dist(b, a)));
      REQUIRE(std::abs(gf::dot(w, c - a)) <= 1e-12 * (1 + dist(c, a)));
      (void)nrm;
    }
  }
  // Random points far from small triangles mostly land in the vertex and edge regions: every kind is seen.
  CHECK(faces > 0);
  CHECK(edges > 0);
  CHECK(vertices > 0);
}

TEST_CASE("mesh: binary and ASCII STL files read back the triangles written", "[mesh]") {
  gf::test::TempDir dir("stl_round_trip");
  const gf::TriangleSoup ring = gf::annulus_triangles({0.01, -0.02, 0.3}, {0.2, 0.1, 1.0}, 0.02, 0.07, 24);
  const auto bin = dir.path / "ring_binary.stl", txt = dir.path / "ring_ascii.stl";
  gf::write_stl_binary(bin, ring);
  gf::write_stl_ascii(txt, ring);
  const gf::TriangleSoup b = gf::read_stl(bin), a = gf::read_stl(txt);
  REQUIRE(b.binary);
  REQUIRE_FALSE(a.binary);
  REQUIRE(b.size() == ring.size());
  REQUIRE(a.size() == ring.size());
  for (std::size_t k = 0; k < ring.corners.size(); ++k) {
    // Binary STL stores floats: within half a float's ulp (2^-24 relative); ASCII with 17 digits exactly.
    const Vec3d& x = ring.corners[k];
    const double tol = 0.6e-7 * std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
    REQUIRE(dist(b.corners[k], x) <= tol * std::sqrt(3.0));
    REQUIRE(a.corners[k].x == x.x);
    REQUIRE(a.corners[k].y == x.y);
    REQUIRE(a.corners[k].z == x.z);
  }
  // The facet lines are remembered for messages: the second facet of the ASCII file starts on line 9.
  REQUIRE(a.at[1] == 9);
  REQUIRE(b.at[1] == 2);
  // Welded, both give the annulus's 48 vertices and one flat region.
  const gf::TriangleMesh mb = gf::build_mesh(b), ma = gf::build_mesh(a);
  REQUIRE(ma.vertex.size() == 48);
  REQUIRE(mb.vertex.size() == 48);
  REQUIRE(ma.regions == 1);
  REQUIRE(mb.regions == 1);
}

TEST_CASE("mesh: the primitives weld into the expected vertices, edges and flat regions", "[mesh]") {
  SECTION("plate") {
    const gf::TriangleMesh m = gf::build_mesh(gf::plate_triangles({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 0.1, 0.05, 8, 5));
    REQUIRE(m.triangles() == 80);
    REQUIRE(m.vertex.size() == 9 * 6);
    REQUIRE(m.edge_start.size() - 1 == 3 * 40 + 8 + 5);
    REQUIRE(m.regions == 1);
    for (const Vec3d& n : m.normal) REQUIRE(n.z == Approx(1.0));
    // Boundary edges have one triangle, the others two.
    std::size_t boundary = 0;
    for (std::size_t e = 0; e + 1 < m.edge_start.size(); ++e) boundary += m.edge_start[e + 1] - m.edge_start[e] == 1;
    REQUIRE(boundary == 2 * (8 + 5));
  }
  SECTION("cylinder mantle: closed around, one flat strip per segment") {
    const gf::TriangleMesh m = gf::build_mesh(gf::cylinder_triangles({0, 0, 0}, {0, 0, 1}, 0.1, 0.04, 36, 3));
    REQUIRE(m.vertex.size() == 36 * 4);
    REQUIRE(m.regions == 36);
    std::size_t boundary = 0;
    for (std::size_t e = 0; e + 1 < m.edge_start.size(); ++e) boundary += m.edge_start[e + 1] - m.edge_start[e] == 1;
    REQUIRE(boundary == 2 * 36);  // the two rims only: the seam is closed
  }
  SECTION("disc: fanned from its centre") {
    const gf::TriangleMesh m = gf::build_mesh(gf::annulus_triangles({0, 0, 0}, {1, 0, 0}, 0.0, 0.1, 16));
    REQUIRE(m.vertex.size() == 17);
    REQUIRE(m.regions == 1);
  }
}

TEST_CASE("mesh: the contact grid lists every triangle within reach of a point", "[mesh]") {
  const gf::TriangleMesh m = gf::build_mesh(gf::cylinder_triangles({0.01, 0, 0}, {0.3, 1, 0.2}, 0.05, 0.06, 40, 6));
  const double reach = 0.004;
  const gf::TriangleGrid grid = gf::build_triangle_grid(m, reach);
  std::mt19937_64 rng(3);
  std::size_t found = 0;
  for (int k = 0; k < 4000; ++k) {
    const Vec3d p = Vec3d{0.01, 0, 0} + random_vec(rng, 0.06);
    const auto near = grid.near(p);
    for (std::size_t t = 0; t < m.triangles(); ++t) {
      const double d = dist(p, gf::closest_point_on_triangle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)).q);
      if (d >= reach) continue;
      ++found;
      REQUIRE(std::find(near.begin(), near.end(), static_cast<std::uint32_t>(t)) != near.end());
    }
  }
  REQUIRE(found > 100);  // the test saw triangles within reach
}

TEST_CASE("mesh: bad STL files are refused naming the file, the place and the fix", "[mesh][errors]") {
  gf::test::TempDir dir("stl_errors");
  SECTION("missing file") {
    const std::string m = message_of([&] { gf::read_stl(dir.path / "nowhere.stl"); });
    CHECK_THAT(m, Catch::Contains("nowhere.stl"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
  }
  SECTION("truncated binary file") {
    const gf::TriangleSoup plate = gf::plate_triangles({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 1, 1, 2, 2);
    const auto p = dir.path / "cut.stl";
    gf::write_stl_binary(p, plate);
    const std::string bytes = gf::test::read_file(p);
    const auto cut = dir.write("cut.stl", bytes.substr(0, bytes.size() - 30));
    const std::string m = message_of([&] { gf::read_stl(cut); });
    CHECK_THAT(m, Catch::Contains("cut.stl"));
    CHECK_THAT(m, Catch::Contains("8 triangles"));
    CHECK_THAT(m, Catch::Contains("truncated"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
  }
  SECTION("ASCII syntax error, with its line") {
    const auto p = dir.write("bad.stl", "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                                        "   vertx 0 1 0\n  endloop\n endfacet\nendsolid s\n");
    const std::string m = message_of([&] { gf::read_stl(p); });
    CHECK_THAT(m, Catch::Contains("bad.stl:6:"));
    CHECK_THAT(m, Catch::Contains("vertex x y z"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
  }
  SECTION("ASCII file cut inside a solid") {
    const auto p = dir.write("short.stl", "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n");
    const std::string m = message_of([&] { gf::read_stl(p); });
    CHECK_THAT(m, Catch::Contains("short.stl:"));
    CHECK_THAT(m, Catch::Contains("the file ends"));
  }
  SECTION("NaN coordinate") {
    const auto p = dir.write("nan.stl", "solid s\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex nan 0 0\n"
                                        "   vertex 0 1 0\n  endloop\n endfacet\nendsolid s\n");
    const std::string m = message_of([&] { gf::read_stl(p); });
    CHECK_THAT(m, Catch::Contains("nan.stl:5:"));
    CHECK_THAT(m, Catch::Contains("finite"));
  }
  SECTION("degenerate triangle, named by its facet's line") {
    const auto p = dir.write("flat.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                         "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                                         "vertex 2 0 0\nendloop\nendfacet\nendsolid s\n");
    const std::string m = message_of([&] { gf::build_mesh(gf::read_stl(p)); });
    CHECK_THAT(m, Catch::Contains("flat.stl:9:"));
    CHECK_THAT(m, Catch::Contains("degenerate"));
    CHECK_THAT(m, Catch::Contains("Fix:"));
  }
  SECTION("no triangles") {
    const auto p = dir.write("empty.stl", "solid nothing\nendsolid nothing\n");
    const std::string m = message_of([&] { gf::build_mesh(gf::read_stl(p)); });
    CHECK_THAT(m, Catch::Contains("empty.stl"));
    CHECK_THAT(m, Catch::Contains("no triangles"));
  }
  SECTION("neither binary nor ASCII") {
    const auto p = dir.write("junk.stl", std::string(200, 'x'));
    const std::string m = message_of([&] { gf::read_stl(p); });
    CHECK_THAT(m, Catch::Contains("junk.stl"));
    CHECK_THAT(m, Catch::Contains("neither"));
  }
}
