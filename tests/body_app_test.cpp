// grainflow check and run on scenes of composite grains: the series (with the remaining fraction
// above an outlet), the state frames, the side-view pictures and summary.json of a small gated bin
// run through the command line; a run resumed from its checkpoint equal to the bit to one never
// stopped; spheres in the same scene refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "systems/bodies/bodies.hpp"
#include "systems/output/body_outputs.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

// Eight 20 mm cubes in a 100 mm square bin of four planes, on a fixed floor of two slabs with a
// 40 mm gap closed by a fixed gate that is removed at t = 0.05 s of the main stage; a sink 0.1 m
// below takes the cubes that fell through.
const std::string kBin = R"(
[run]
dt = 2.0e-5
duration = 0.35
skin = 1.0e-3

[contact]
model = "linear_spring_dashpot"
kn = 2.0e4
kt = 1.0e4
kr = 0.0
en = 0.3
et = 0.3
er = 0.3
friction = 0.3
rolling_friction = 0.0

[[wall]]
type = "plane"
point = [-0.05, 0.0, 0.0]
normal = [1.0, 0.0, 0.0]
[[wall]]
type = "plane"
point = [0.05, 0.0, 0.0]
normal = [-1.0, 0.0, 0.0]
[[wall]]
type = "plane"
point = [0.0, 0.0, -0.025]
normal = [0.0, 0.0, 1.0]
[[wall]]
type = "plane"
point = [0.0, 0.0, 0.025]
normal = [0.0, 0.0, -1.0]

[[shape]]
name = "cube"
kind = "box"
size = [0.018, 0.018, 0.018]
radius = 0.001
density = 1000.0
[[shape]]
name = "floor"
kind = "box"
size = [0.03, 0.01, 0.05]
radius = 0.001
density = 1000.0
[[shape]]
name = "gate"
kind = "box"
size = [0.04, 0.01, 0.05]
radius = 0.001
density = 1000.0

[[bodies]]
shape = "floor"
fixed = true
positions = [[-0.035, -0.005, 0.0], [0.035, -0.005, 0.0]]
[[bodies]]
shape = "gate"
fixed = true
remove_at = 0.05
positions = [[0.0, -0.005, 0.0]]
[[bodies]]
shape = "cube"
group = 1
count = 8
orientation = "random"
seed = 3
region = { shape = "box", lo = [-0.045, 0.02, -0.02], hi = [0.045, 0.15, 0.02] }

[settle]
time = 0.3

[analysis]
outlet_height = 0.0

[sink]
height = -0.1

[output]
series_interval = 0.01
frame_interval = 0.1
picture_interval = 0.1
picture_colour = "layer"
)";

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

}  // namespace

TEST_CASE("body scene: check and run through the command line write series, frames and pictures", "[bodies][cli]") {
  gf::test::TempDir dir("body_app_cli");
  const auto scene = dir.write("bin.toml", kBin);
  const gf::test::Exit check = gf::test::run_cli(dir, "check " + gf::test::quote(scene.string()));
  INFO("check: " << check.out << check.err);
  REQUIRE(check.code == 0);
  CHECK_THAT(check.out, Catch::Contains("8 moving, 3 fixed (1 removed at a time)"));
  CHECK_THAT(check.out, Catch::Contains("timed_body_removal"));

  const std::filesystem::path out = dir.path / "out";
  const gf::test::Exit run = gf::test::run_cli(
      dir, "run " + gf::test::quote(scene.string()) + " --quiet --out " + gf::test::quote(out.string()));
  INFO("run: " << run.err);
  REQUIRE(run.code == 0);

  const std::vector<std::string> rows = gf::test::read_lines(out / "series.csv");
  REQUIRE(rows.size() == 37);  // the header, t = 0 .. 0.35 every 0.01 s
  CHECK(rows[0] == "time,ke_translational,ke_rotational,contacts,wall_contacts,max_overlap_ratio,moving,"
                   "remaining_fraction");
  const auto first = split(rows[1]), before = split(rows[5]), last = split(rows.back());
  // Settled on the closed gate: everything above the outlet, nearly at rest, overlaps small.
  CHECK(std::stod(first[7]) == 1.0);
  CHECK(std::stod(first[1]) < 1e-4);
  CHECK(std::stod(before[7]) == 1.0);
  CHECK(std::stod(first[5]) < 0.05);
  CHECK(std::stod(first[6]) == 8);
  // The gate opened at 0.05 s: cubes fell through the 40 mm gap into the sink.
  const double remaining = std::stod(last[7]);
  INFO("remaining fraction at the end: " << remaining);
  CHECK(remaining < 1.0);
  CHECK(std::stod(last[6]) < 8);  // the sink took them
  for (std::size_t k = 2; k < rows.size(); ++k)
    CHECK(std::stod(split(rows[k])[7]) <= std::stod(split(rows[k - 1])[7]));

  // Frames: one per 0.1 s and the last state; every body, the gate removed in the later ones.
  const std::vector<std::string> index = gf::test::read_lines(out / "frames" / "frames.csv");
  REQUIRE(index.size() == 6);  // header, 0, 0.1, 0.2, 0.3, 0.35
  const std::vector<std::string> f0 = gf::test::read_lines(out / "frames" / "frame_000000.csv");
  const std::vector<std::string> f4 = gf::test::read_lines(out / "frames" / "frame_000004.csv");
  REQUIRE(f0.size() == 12);
  CHECK(f0[0] == "id,shape,group,layer,motion,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  CHECK(split(f0[3])[1] == "gate");
  CHECK(split(f0[3])[4] == "fixed");
  CHECK(split(f4[3])[4] == "removed");
  CHECK(split(f0[4])[1] == "cube");
  CHECK(split(f0[4])[2] == "1");
  // The same frames for ParaView: a cell per member (each box one hull of 8 corners), removed bodies (the gate,
  // the cubes in the sink) left out.
  const std::string pvd = gf::test::read_file(out / "bodies.pvd");
  std::size_t entries = 0;
  for (std::size_t at = pvd.find("<DataSet"); at != std::string::npos; at = pvd.find("<DataSet", at + 1)) ++entries;
  CHECK(entries == 5);
  const std::string v0 = gf::test::read_file(out / "bodies" / "bodies_000000.vtu");
  const std::string v4 = gf::test::read_file(out / "bodies" / "bodies_000004.vtu");
  CHECK_THAT(v0, Catch::Contains("NumberOfPoints=\"88\" NumberOfCells=\"11\""));
  int kept = 0;
  for (std::size_t k = 1; k < f4.size(); ++k) kept += split(f4[k])[4] != "removed";
  CHECK_THAT(v4, Catch::Contains("NumberOfPoints=\"" + std::to_string(8 * kept) + "\" NumberOfCells=\"" +
                                 std::to_string(kept) + "\""));
  CHECK_THAT(v0, Catch::Contains("Name=\"radius\""));
  // The four fixed planes, drawn across the bodies' box, in one file listed at every frame.
  CHECK(std::filesystem::exists(out / "walls" / "walls_000000.vtp"));
  CHECK_FALSE(std::filesystem::exists(out / "walls" / "walls_000001.vtp"));
  CHECK_THAT(gf::test::read_file(out / "walls" / "walls_000000.vtp"), Catch::Contains("NumberOfPolys=\"8\""));
  const auto q = split(f0[4]);
  const double qn = std::hypot(std::hypot(std::stod(q[8]), std::stod(q[9])), std::hypot(std::stod(q[10]), std::stod(q[11])));
  CHECK(std::abs(qn - 1.0) < 1e-12);

  // Pictures at 0, 0.1, 0.2 and 0.3 s, PNG files with their colouring stated.
  for (const char* name : {"time_0000.0000.png", "time_0000.1000.png", "time_0000.2000.png", "time_0000.3000.png"}) {
    const std::string png = gf::test::read_file(out / "pictures" / name);
    INFO(name);
    REQUIRE(png.size() > 100);
    CHECK(png.substr(1, 3) == "PNG");
    CHECK(png.find("five layers") != std::string::npos);
  }
  const std::string summary = gf::test::read_file(out / "summary.json");
  CHECK_THAT(summary, Catch::Contains("\"status\": \"completed\"") && Catch::Contains("remaining_fraction"));
}

TEST_CASE("body scene: spheres that cannot be bodies are refused by check and run naming the fix", "[bodies][cli]") {
  gf::test::TempDir dir("body_app_refused");
  const auto mixed = dir.write("mixed.toml", kBin + "\n[[species]]\nname = \"glass\"\ndiameter = 0.002\ndensity = 2500\n"
                                                    "rotates = false\n");
  for (const char* command : {"check ", "run "}) {
    const gf::test::Exit e = gf::test::run_cli(dir, command + gf::test::quote(mixed.string()));
    INFO(command << e.err);
    CHECK(e.code == 1);
    CHECK_THAT(e.err, Catch::Contains("mixed.toml") && Catch::Contains("species[0].rotates") &&
                          Catch::Contains("always rotates") && Catch::Contains("Fix:"));
  }
}

TEST_CASE("body scene: a run resumed from its checkpoint ends bit-identical to one never stopped", "[bodies][cli]") {
  // The gate opens at 0.05 s; the run stops at 0.2 s (--steps), while cubes fall through the outlet,
  // and is resumed to 0.35 s. Series, frames and pictures must equal the uninterrupted run's bytes.
  gf::test::TempDir dir("body_app_resume");
  const auto scene = dir.write("bin.toml", kBin);
  const std::string q = gf::test::quote(scene.string());
  const std::filesystem::path whole = dir.path / "whole", parts = dir.path / "parts";
  REQUIRE(gf::test::run_cli(dir, "run " + q + " --quiet --out " + gf::test::quote(whole.string())).code == 0);
  REQUIRE(gf::test::run_cli(dir, "run " + q + " --quiet --steps 10000 --out " + gf::test::quote(parts.string())).code == 0);
  const std::filesystem::path ckpt = parts / "checkpoints" / "checkpoint.gfc";
  REQUIRE(std::filesystem::exists(ckpt));
  const gf::test::Exit r = gf::test::run_cli(
      dir, "run " + q + " --quiet --out " + gf::test::quote(parts.string()) + " --resume " + gf::test::quote(ckpt.string()));
  INFO(r.err);
  REQUIRE(r.code == 0);
  CHECK(gf::test::read_file(parts / "series.csv") == gf::test::read_file(whole / "series.csv"));
  for (const char* f : {"frame_000002.csv", "frame_000003.csv", "frame_000004.csv", "frames.csv"}) {
    INFO(f);
    CHECK(gf::test::read_file(parts / "frames" / f) == gf::test::read_file(whole / "frames" / f));
  }
  CHECK(gf::test::read_file(parts / "pictures" / "time_0000.3000.png") ==
        gf::test::read_file(whole / "pictures" / "time_0000.3000.png"));
  // The removed gate and the sunk cubes are part of the state carried over.
  CHECK_THAT(gf::test::read_file(parts / "frames" / "frame_000004.csv"), Catch::Contains("gate,1,-1,removed"));
  // A checkpoint of another scene is refused naming what differs.
  const auto other = dir.write("other.toml", kBin + "\n[[bodies]]\nshape = \"cube\"\npositions = [[0.0, 0.3, 0.0]]\n");
  const gf::test::Exit wrong = gf::test::run_cli(dir, "run " + gf::test::quote(other.string()) + " --quiet --out " +
                                                          gf::test::quote((dir.path / "o").string()) + " --resume " +
                                                          gf::test::quote(ckpt.string()));
  CHECK(wrong.code != 0);
  CHECK_THAT(wrong.err, Catch::Contains("body count") && Catch::Contains("Fix:"));
}

TEST_CASE("body layers are five equal counts by height, and the remaining fraction counts moving bodies above") {
  gf::Bodies b;
  for (int i = 0; i < 10; ++i) {
    gf::BodyRow row;
    row.x = {0.0, 0.1 * (9 - i), 0.0};
    row.mass = 1.0;
    row.inertia = {1.0, 1.0, 1.0};
    b.push(row);
  }
  gf::BodyRow wall;
  wall.mass = 1.0;
  wall.inertia = {1.0, 1.0, 1.0};
  wall.motion = gf::Motion::fixed;
  wall.x = {0.0, 5.0, 0.0};
  b.push(wall);
  const gf::Gravity g{0.0, -9.81, 0.0};
  const std::vector<int> layers = gf::body_layers(b, g);
  CHECK(layers == std::vector<int>{4, 4, 3, 3, 2, 2, 1, 1, 0, 0, -1});
  CHECK(gf::remaining_fraction(b, g, 0.45, 10) == Approx(0.5));
  gf::remove_body(b, 0);
  CHECK(gf::remaining_fraction(b, g, 0.45, 10) == Approx(0.4));
  CHECK(gf::remaining_fraction(b, gf::Gravity{9.81, 0.0, 0.0}, -1.0, 10) == Approx(0.9));
}

TEST_CASE("body scene: a [[bodies]] file restarts the moving bodies of its shape from a frame's state", "[bodies][cli]") {
  gf::test::TempDir dir("body_app_frame_restart");
  const auto scene = dir.write("bin.toml", kBin);
  const std::filesystem::path out = dir.path / "out";
  REQUIRE(gf::test::run_cli(dir, "run " + gf::test::quote(scene.string()) + " --quiet --steps 5000 --out " +
                                     gf::test::quote(out.string())).code == 0);
  const std::filesystem::path frame = out / "frames" / "frame_000001.csv";  // t = 0.1 s, the gate open
  std::string text = kBin;
  const std::string table = "count = 8\norientation = \"random\"\nseed = 3\n"
                            "region = { shape = \"box\", lo = [-0.045, 0.02, -0.02], hi = [0.045, 0.15, 0.02] }";
  const auto at = text.find(table);
  REQUIRE(at != std::string::npos);
  text.replace(at, table.size(), "file = \"" + frame.string() + "\"");
  // The gate was open at 0.1 s, with cubes in the outlet: the restart keeps it out of their way.
  const std::string gate = "remove_at = 0.05\npositions = [[0.0, -0.005, 0.0]]";
  REQUIRE(text.find(gate) != std::string::npos);
  text.replace(text.find(gate), gate.size(), "remove_at = 0.05\npositions = [[0.0, -0.5, 0.0]]");
  gf::DemSimulation sim = gf::DemSimulation::from_text(text);
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const std::vector<std::string> rows = gf::test::read_lines(frame);
  std::size_t moving_cubes = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto f = split(rows[k]);
    if (f[1] != "cube" || f[4] != "moving") continue;
    const std::size_t i = 3 + moving_cubes++;  // after the two floors and the gate
    REQUIRE(i < b.n);
    INFO("frame row " << k);
    CHECK(b.pos.x[i] == std::stod(f[5]));
    CHECK(b.pos.y[i] == std::stod(f[6]));
    CHECK(b.pos.z[i] == std::stod(f[7]));
    CHECK(b.vel.y[i] == std::stod(f[13]));
    CHECK(b.omega.z[i] == std::stod(f[17]));
    CHECK(b.moving(i));
  }
  CHECK(moving_cubes >= 1);
  CHECK(b.n == 3 + moving_cubes);
  // Its own frame at t = 0 repeats the loaded state: the orientation to round-off, the rest exactly.
  const std::filesystem::path again = dir.path / "again";
  const auto restart = dir.write("restart.toml", text);
  REQUIRE(gf::test::run_cli(dir, "run " + gf::test::quote(restart.string()) + " --quiet --steps 1 --set settle.time=0"
                                     " --out " + gf::test::quote(again.string())).code == 0);
  const std::vector<std::string> first = gf::test::read_lines(again / "frames" / "frame_000000.csv");
  std::size_t r = 1;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const auto f = split(rows[k]);
    if (f[1] != "cube" || f[4] != "moving") continue;
    const auto g = split(first[3 + r++]);
    for (std::size_t c : {5, 6, 7, 12, 13, 14, 15, 16, 17}) CHECK(g[c] == f[c]);
    for (std::size_t c : {8, 9, 10, 11}) CHECK(std::abs(std::stod(g[c]) - std::stod(f[c])) < 1e-14);
  }
  // A file without the header is refused naming the key.
  const auto junk = dir.write("junk.csv", "x,y,z\n1,2,3\n");
  text.replace(text.find(frame.string()), frame.string().size(), junk.string());
  CHECK_THROWS_WITH(gf::DemSimulation::from_text(text), Catch::Contains("bodies[2].file") && Catch::Contains("header"));
}
