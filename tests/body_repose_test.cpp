// The angle of repose of composite grains (systems/analysis/body_repose.hpp, read from a scene's
// [[analysis.repose]]): a member's top is the highest point of its dilated core, and a crater of
// cubes stacked on a lattice is measured within the staircase bound of tests/repose_test.cpp, its
// region leaving out the ledges beside it. A run reports each heap in summary.json, and bad tables
// are refused with the key and the fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "systems/analysis/body_repose.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/body_test_support.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kEdge = 0.01;  // m, the cubes' outer edge and the lattice pitch
const gf::V3<double> kUp{0, 1, 0};

std::string scene(const std::string& positions, const std::string& analysis = "") {
  return gf::test::body_scene("duration = 0.0\n",
                              "[[shape]]\nname = \"cube\"\nkind = \"box\"\nsize = [0.01, 0.01, 0.01]\nradius = 0.001\n"
                              "density = 2500.0\n\n[[bodies]]\nshape = \"cube\"\npositions = [" + positions + "]\n\n" + analysis);
}

std::string point(double x, double y, double z) {
  std::ostringstream s;
  s.precision(17);
  s << "[" << x << ", " << y << ", " << z << "], ";
  return s.str();
}

std::string load_error(const std::string& text) {
  return gf::test::scene_error_of([&] { gf::DemSimulation::from_text(text); });
}

gf::ReposeSpec crater_spec(bool band) {
  gf::ReposeSpec s;
  s.geometry = gf::ReposeSpec::Geometry::crater;
  s.across = {1, 0, 0};
  s.settings.column = 2 * kEdge;
  s.has_region = band;
  s.lo = {-1, -1, -0.035};
  s.hi = {1, 1, 0.035};
  return s;
}

}  // namespace

TEST_CASE("body repose: a member's top is the highest point of its dilated core") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene(point(0.1, 0.2, 0.3)));
  gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const gf::Members& m = sim.world().tables.get<gf::Members>();
  // Turned by 30 degrees about z: the core's half edges (0.004 m, inset by r = 0.001) reach
  // 0.004 (sin 30 + cos 30) above the centre, and the dilation r above that.
  // The turn is applied after the body's own rotation (shape frame to principal axes), so the cube's
  // faces turn about the world z axis whatever principal axes its equal moments were given.
  const double t = 30.0 * kDeg;
  const Eigen::Quaterniond turned =
      Eigen::Quaterniond(Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ())) * Eigen::Quaterniond(b.q.w[0], b.q.x[0], b.q.y[0], b.q.z[0]);
  b.q.w[0] = turned.w();
  b.q.x[0] = turned.x();
  b.q.y[0] = turned.y();
  b.q.z[0] = turned.z();
  const gf::MemberTops tops = gf::member_tops(b, m, kUp, gf::ReposeSpec{});
  REQUIRE(tops.r.size() == 1);
  CHECK(tops.y[0] == Approx(0.2).margin(1e-15));
  CHECK(tops.r[0] == Approx(0.004 * (std::sin(t) + std::cos(t)) + 0.001).margin(1e-15));
  // A region that misses the member leaves it out.
  gf::ReposeSpec away;
  away.has_region = true;
  away.lo = {1, 1, 1};
  away.hi = {2, 2, 2};
  CHECK(gf::member_tops(b, m, kUp, away).r.empty());
}

TEST_CASE("body repose: a crater of cubes, measured in a band across it") {
  // Cubes on a lattice of pitch kEdge: a V at 30 degrees about x = 0 down to 1 cm above the floor,
  // in a band |z| <= 3 cm; beside it, ledges at |z| = 6 to 8 cm as high as the V's rim. The band's
  // surface is a staircase within one pitch of the V (a cube's top is its centre + kEdge / 2), so the
  // slope lies within 0.75 pitch / span of tan 30 degrees (tests/repose_test.cpp derives the bound).
  const double a = 30.0 * kDeg, top = 0.12;
  std::string pos;
  for (int i = -20; i <= 20; ++i)
    for (int k = -8; k <= 8; ++k)
      for (int j = 0; (j + 0.5) * kEdge <= top; ++j) {
        const double x = i * kEdge, y = (j + 0.5) * kEdge, z = k * kEdge;
        const bool band = std::abs(k) <= 3, ledge = std::abs(k) >= 6;
        if ((band && y <= std::min(top, 0.01 + std::abs(x) * std::tan(a))) || ledge) pos += point(x, y, z);
      }
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene(pos));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const gf::Members& m = sim.world().tables.get<gf::Members>();
  const gf::Repose r = gf::body_repose(b, m, kUp, crater_spec(true));
  for (const gf::ReposeFlank* f : {&r.first, &r.second}) {
    REQUIRE(f->columns >= 5);
    const double span = f->s_to - f->s_from;
    INFO("measured " << f->angle / kDeg << " deg over " << span << " m");
    CHECK(std::abs(std::tan(f->angle) - std::tan(a)) <= 0.75 * kEdge / span + 1e-12);
  }
  CHECK(r.first.slope < 0.0);
  CHECK(r.second.slope > 0.0);
  // Without the band the ledges set every column's top: no crater is left to measure.
  const gf::Repose all = gf::body_repose(b, m, kUp, crater_spec(false));
  CHECK(!(std::abs(all.first.angle - a) < 5 * kDeg));
}

TEST_CASE("body repose: a run reports each heap in summary.json") {
  gf::test::TempDir dir("body_repose");
  std::string pos;
  for (int i = -6; i <= 6; ++i)
    for (int j = 0; j <= 6 - std::abs(i); ++j) pos += point(i * kEdge, (j + 0.5) * kEdge, 0.0);
  const std::filesystem::path file = dir.path / "ridge.toml";
  {
    std::ofstream f(file);
    f << scene(pos, "[[analysis.repose]]\nname = \"ridge\"\ngeometry = \"ridge\"\nacross = [1.0, 0.0, 0.0]\n"
                    "column = 0.01\nrank = 1\n");
  }
  const gf::test::Exit e = gf::test::run_cli(
      dir, "run " + gf::test::quote(file.string()) + " --quiet --out " + gf::test::quote((dir.path / "out").string()));
  REQUIRE(e.code == 0);
  const auto j = nlohmann::json::parse(gf::test::read_file(dir.path / "out" / "summary.json"));
  REQUIRE(j.contains("repose"));
  // A staircase of one cube per column: slope exactly 1 (45 degrees) on both flanks.
  CHECK(j["repose"]["ridge"]["first"]["angle_deg"].get<double>() == Approx(45.0).margin(1e-9));
  CHECK(j["repose"]["ridge"]["second"]["angle_deg"].get<double>() == Approx(45.0).margin(1e-9));
}

TEST_CASE("body repose: bad tables are refused with the key and the fix") {
  const std::string one = point(0, 0.005, 0);
  auto with = [&](const std::string& keys) { return scene(one, "[[analysis.repose]]\nname = \"h\"\n" + keys); };
  CHECK_THAT(load_error(with("geometry = \"heap\"\nacross = [1.0, 0.0, 0.0]\ncentre = [0.0, 0.0, 0.0]\ncolumn = 0.01\n")),
             Catch::Contains("across") && Catch::Contains("centre = [x, y, z]"));
  CHECK_THAT(load_error(with("geometry = \"crater\"\nacross = [0.0, 2.0, 0.0]\ncolumn = 0.01\n")),
             Catch::Contains("across") && Catch::Contains("horizontal"));
  CHECK_THAT(load_error(with("geometry = \"ridge\"\nacross = [1.0, 0.0, 0.0]\ncolumn = 0.0\n")), Catch::Contains("column"));
  CHECK_THAT(load_error(with("geometry = \"ridge\"\nacross = [1.0, 0.0, 0.0]\ncolumn = 0.01\nlower = 0.9\nupper = 0.5\n")),
             Catch::Contains("upper"));
  CHECK_THAT(load_error(with("geometry = \"ridge\"\nacross = [1.0, 0.0, 0.0]\ncolumn = 0.01\n"
                             "region = { lo = [0.0, 0.0, 0.0], hi = [1.0, -1.0, 1.0] }\n")),
             Catch::Contains("hi") && Catch::Contains("hi > lo"));
  CHECK_THAT(load_error(with("geometry = \"cone\"\ncentre = [0.0, 0.0, 0.0]\ncolumn = 0.01\n")), Catch::Contains("geometry"));
  const std::string twice = "geometry = \"heap\"\ncentre = [0.0, 0.0, 0.0]\ncolumn = 0.01\n";
  CHECK_THAT(load_error(scene(one, "[[analysis.repose]]\nname = \"h\"\n" + twice + "\n[[analysis.repose]]\nname = \"h\"\n" +
                                       twice)),
             Catch::Contains("name") && Catch::Contains("a name of its own"));
}
