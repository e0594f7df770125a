// The walls as ParaView surfaces (systems/output/wall_surfaces.hpp): a box's faces are its rectangles,
// a drum its mantle and two end discs, an unbounded plane is cut by the scene's box, a turning or
// vibrating wall is drawn where the contacts place it, and a run writes walls.pvd beside frames.pvd.
#include "systems/output/wall_surfaces.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <numbers>

#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::Vec3d;

namespace {

// The triangles' total area per wall index.
std::vector<double> areas(const gf::WallSurface& s, std::size_t walls) {
  std::vector<double> a(walls, 0.0);
  for (std::size_t k = 0; k < s.triangles.size(); ++k) {
    const auto& t = s.triangles[k];
    const Vec3d e1 = s.points[t[1]] - s.points[t[0]], e2 = s.points[t[2]] - s.points[t[0]];
    const Vec3d c = cross(e1, e2);
    a[static_cast<std::size_t>(s.wall[k])] += 0.5 * std::sqrt(dot(c, c));
  }
  return a;
}

}  // namespace

TEST_CASE("a box's faces are its rectangles, each with its wall index") {
  DemSimulation sim = DemSimulation::from_text(gf::test::binary_box_scene(20, 0));
  const gf::Walls& walls = sim.world().resources.get<gf::Walls>();
  const gf::SceneBox box = gf::scene_box(sim.grains(), walls, nullptr);
  const gf::WallSurface s = gf::wall_surface(walls, nullptr, 0.0, box);
  REQUIRE(s.triangles.size() == 12);
  const std::vector<double> a = areas(s, 6);
  // The box is 20 x 30 x 20 mm: the x faces 30 x 20, the y faces 20 x 20, the z faces 20 x 30 (mm^2).
  CHECK(a[0] == Approx(6e-4));
  CHECK(a[2] == Approx(4e-4));
  CHECK(a[5] == Approx(6e-4));
  constexpr double e = 1e-15;  // the placement adds and takes back the rotation point
  for (const Vec3d& p : s.points) {
    INFO(p.x << " " << p.y << " " << p.z);
    CHECK((p.x >= -e && p.x <= 0.02 + e && p.y >= -e && p.y <= 0.03 + e));
  }
  CHECK_FALSE(gf::walls_move(walls, nullptr));
}

TEST_CASE("a drum is its mantle over its length and two end discs, turned with it") {
  DemSimulation sim = DemSimulation::from_text(gf::test::small_drum_scene(9.81));
  gf::Walls walls = sim.world().resources.get<gf::Walls>();
  const gf::SceneBox box = gf::scene_box(sim.grains(), walls, nullptr);
  walls.place(0.5);
  const gf::WallSurface s = gf::wall_surface(walls, nullptr, 0.5, box);
  const std::vector<double> a = areas(s, 3);
  // A 96-gon's mantle and discs: 2 pi R L and pi R^2 times sin(2 pi / 96) / (2 pi / 96) (0.9993).
  const double shrink = std::sin(2.0 * std::numbers::pi / 96) / (2.0 * std::numbers::pi / 96);
  CHECK(a[0] == Approx(2.0 * std::numbers::pi * 0.012 * 0.006 * shrink).epsilon(1e-3));
  CHECK(a[1] == Approx(std::numbers::pi * 0.012 * 0.012 * shrink).epsilon(1e-3));
  CHECK(a[2] == Approx(a[1]));
  for (const Vec3d& p : s.points) CHECK(std::abs(p.z) <= 0.003 + 1e-12);
  CHECK(gf::walls_move(walls, nullptr));
}

TEST_CASE("an unbounded plane is drawn across the scene's box, and a vibrating one where it is") {
  std::string scene = gf::test::binary_box_scene(20, 0);
  scene += "[[wall]]\ntype = \"plane\"\nname = \"lid\"\npoint = [0.0, 0.031, 0.0]\nnormal = [0.0, -1.0, 0.0]\n"
           "vibration_amplitude = [0.0, 0.001, 0.0]\nvibration_frequency = 10.0\n";
  DemSimulation sim = DemSimulation::from_text(scene);
  gf::Walls walls = sim.world().resources.get<gf::Walls>();
  const gf::SceneBox box = gf::scene_box(sim.grains(), walls, nullptr);
  walls.place(0.025);  // a quarter period: the lid is up by the amplitude
  const gf::WallSurface s = gf::wall_surface(walls, nullptr, 0.025, box);
  double lid_y = 0.0;
  for (std::size_t k = 0; k < s.triangles.size(); ++k)
    if (s.wall[k] == 6) lid_y = s.points[s.triangles[k][0]].y;
  CHECK(lid_y == Approx(0.032));
  // Across the scene's box: the box wall spans 20 x 20 mm across y; the box reaches the lid's point at
  // y = 31 mm and grows by a tenth of that on every side.
  CHECK(areas(s, 7)[6] == Approx(0.0262 * 0.0262));
}

TEST_CASE("a run writes walls.pvd with the frames' times") {
  const gf::test::TempDir dir("wall_surfaces");
  const std::filesystem::path scene = dir.path / "drum.toml", out = dir.path / "run";
  std::ofstream(scene) << gf::test::small_drum_scene(9.81);
  const gf::test::Exit e = gf::test::run_cli(dir, "run " + gf::test::quote(scene.string()) + " --out " +
                                                       gf::test::quote(out.string()) + " --quiet");
  REQUIRE(e.code == 0);
  const std::string frames = gf::test::read_file(out / "frames.pvd"), walls = gf::test::read_file(out / "walls.pvd");
  REQUIRE_FALSE(walls.empty());
  // The same timesteps, the walls' files beside the grains'.
  const auto count = [](const std::string& s, const std::string& w) {
    std::size_t n = 0;
    for (std::size_t at = s.find(w); at != std::string::npos; at = s.find(w, at + 1)) ++n;
    return n;
  };
  CHECK(count(walls, "timestep=") == count(frames, "timestep="));
  CHECK(count(walls, "walls/walls_") == count(frames, "frames/frame_"));
  CHECK(std::filesystem::exists(out / "walls" / "walls_000001.vtp"));
}
