// DEM scenes: every bad scene stops before anything runs with a message naming the file, the line
// and the key (or the fill); the critical-step check and its override; and the command line end to
// end on a tiny scene: outputs of `run`, the report of `check`, exit codes, and a run stopped by
// SIGTERM that keeps every result it wrote.
#include <catch2/catch.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/setup/dem_scene.hpp"
#include "engine/machine_memory.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Contains;
using gf::test::lines_of;
using gf::test::read_file;
using gf::test::read_lines;
using gf::test::Exit;
using gf::test::quote;
using gf::test::run_cli;
using gf::test::TempDir;

namespace {

// 50 glass spheres of 2 mm in a 10 x 20 x 10 mm box. SI units. The smallest collision period is the
// tangential glass-glass term, 3.36e-4 s, so dt = 1e-5 s is 0.03 of it.
const std::string kScene = R"(# tiny test scene (SI units)
[run]
dt = 1.0e-5
duration = 0.01
skin = 1.0e-4
gravity = [0.0, -9.81, 0.0]

[[species]]
name = "glass"
diameter = 2.0e-3
density = 2500.0

[contact]
model = "linear_spring_dashpot"
kn = 1000.0
kt = 600.0
en = 0.3
et = 0.3
friction = 0.3

[[wall]]
type = "box"
lo = [0.0, 0.0, 0.0]
hi = [0.01, 0.02, 0.01]

[[fill]]
kind = "random"
region = { shape = "box", lo = [0.001, 0.001, 0.001], hi = [0.009, 0.019, 0.009] }
count = { glass = 50 }

[output]
series_interval = 1.0e-4
frame_interval = 5.0e-4
)";

// `text` with the first `from` replaced by `to`; the test fails if `from` is absent.
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// 1-based line of the first occurrence of `needle`.
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

// "<file>:<line>:" as the messages start.
std::string at(const fs::path& file, int line) { return file.string() + ":" + std::to_string(line) + ":"; }

// The SceneError message of loading (and, with build = true, building the world of and priming) a scene file;
// "" if it loads. Any other exception escapes and fails the test.
std::string scene_error(const fs::path& file, const std::vector<std::string>& overrides = {}, bool build = false) {
  try {
    gf::DemScene s = gf::load_dem_scene(gf::SceneDoc::load(file, overrides));
    if (build) gf::DemSimulation(std::move(s)).prime();
  } catch (const gf::SceneError& e) {
    return e.what();
  }
  return "";
}

// The collision periods of the test scene, from the closed form T = 2 sqrt(pi^2 + ln^2 e) sqrt(m/k),
// computed here independently of the contact table. Returns the smallest.
double expected_critical_period() {
  const double pi = std::numbers::pi;
  const double r = 1.0e-3, m = 2500.0 * 4.0 / 3.0 * pi * r * r * r;
  const double root = std::sqrt(pi * pi + std::log(0.3) * std::log(0.3));
  auto period = [&](double meff, double k) { return 2.0 * root * std::sqrt(meff / k); };
  const double pair_normal = period(m / 2, 1000.0), pair_tangential = period(2.0 / 7.0 * m / 2, 600.0);
  const double wall_normal = period(m, 1000.0), wall_tangential = period(2.0 / 7.0 * m, 600.0);
  // The tangential pair term must be the smallest, or the message would name another term.
  REQUIRE(pair_tangential < std::min({pair_normal, wall_normal, wall_tangential}));
  return pair_tangential;
}

// The number after `prefix` in `text`, or NaN.
double number_after(const std::string& text, const std::string& prefix) {
  const auto at = text.find(prefix);
  if (at == std::string::npos) return std::nan("");
  const char* b = text.data() + at + prefix.size();
  double v = 0;
  const auto res = std::from_chars(b, text.data() + text.size(), v);
  return res.ec == std::errc() ? v : std::nan("");
}

// ---------------------------------------------------------------------------------------------------------------------
// Running the real binary.

// Every field of a series.csv row as a number: the whole field must parse.
std::vector<double> fields(const std::string& row) {
  std::vector<double> out;
  std::size_t b = 0;
  for (;;) {
    const auto e = row.find(',', b);
    const std::string f = row.substr(b, e == std::string::npos ? std::string::npos : e - b);
    double v = 0;
    const auto res = std::from_chars(f.data(), f.data() + f.size(), v);
    if (res.ec != std::errc() || res.ptr != f.data() + f.size()) return {};
    out.push_back(v);
    if (e == std::string::npos) break;
    b = e + 1;
  }
  return out;
}

const std::string kSeriesHeader =
    "time,angle,ke_translational,ke_rotational,contacts,wall_contacts,max_overlap_ratio,segregation_index";

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
TEST_CASE("dem scene: the test scene itself is valid", "[dem_scene]") {
  // Every error case below is one edit of this scene, so it must load, build and have 50 grains.
  TempDir dir("dem_scene_ok");
  const fs::path f = dir.write("ok.toml", kScene);
  CHECK(scene_error(f, {}, true).empty());
  const gf::DemScene s = gf::load_dem_scene(gf::SceneDoc::load(f));
  CHECK(s.dt == 1.0e-5);
  CHECK(s.critical.term == "tangential, glass-glass");
  // The contact table's period against the closed form: only rounding differs (1e-12 relative).
  CHECK(s.critical.period == Approx(expected_critical_period()).epsilon(1e-12));
  CHECK(gf::planned_grain_count(s) == 50);
}

TEST_CASE("dem scene: bad keys and values name the file, the line and the key", "[dem_scene]") {
  TempDir dir("dem_scene_keys");
  SECTION("a misspelt key in [run]") {
    const std::string text = with(kScene, "skin = 1.0e-4\n", "skin = 1.0e-4\nseeed = 3\n");
    const fs::path f = dir.write("typo.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "seeed")) + " key 'run.seeed'"));
    CHECK_THAT(e, Contains("unknown key 'seeed'"));
    CHECK_THAT(e, Contains("did you mean 'seed'?"));
  }
  SECTION("a misspelt table") {
    const std::string text = with(kScene, "[output]", "[outptu]");
    const fs::path f = dir.write("typo_table.toml", text);
    CHECK_THAT(scene_error(f), Contains(at(f, line_of(text, "[outptu]")) + " key 'outptu'"));
  }
  SECTION("a missing species diameter") {
    const std::string text = with(kScene, "diameter = 2.0e-3\n", "");
    const fs::path f = dir.write("no_diameter.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "[[species]]")) + " key 'species[0].diameter'"));
    CHECK_THAT(e, Contains("missing required key 'diameter'"));
  }
  SECTION("a density past any material") {
    // 1e308 kg/m^3 made masses and time-step terms infinite ("critical period inf s").
    const fs::path f = dir.write("dense.toml", kScene);
    CHECK_THAT(scene_error(f, {"species.0.density=1e308"}),
               Contains("key 'species[0].density'") && Contains("out of range") && Contains("1e6"));
  }
  SECTION("a negative diameter") {
    const std::string text = with(kScene, "diameter = 2.0e-3", "diameter = -2.0e-3");
    const fs::path f = dir.write("negative_diameter.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "diameter = -2.0e-3")) + " key 'species[0].diameter'"));
    CHECK_THAT(e, Contains("-0.002 m is out of range") && Contains("[1e-8, 100]"));
  }
  SECTION("a negative radius") {
    const std::string text =
        with(kScene, R"(region = { shape = "box", lo = [0.001, 0.001, 0.001], hi = [0.009, 0.019, 0.009] })",
             R"(region = { shape = "cylinder", center = [0.005, 0.01, 0.005], axis = [0, 0, 1], radius = -0.003, length = 0.006 })");
    const fs::path f = dir.write("negative_radius.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "radius = -0.003")) + " key 'fill[0].region.radius'"));
    CHECK_THAT(e, Contains("out of range"));
  }
  SECTION("a duration of more steps than a run can count") {
    // 1e14 s at 1e-5 s is 1e19 steps, past the 64-bit step count (it used to wrap to a negative count
    // and 'complete' after 0 steps): refused by the duration's interval now; within it, 1e11 s is still
    // 1e16 steps. A time step of 1e-320 s gave infinitely many: refused as a denormal at the step.
    const fs::path f = dir.write("long.toml", kScene);
    CHECK_THAT(scene_error(f, {"run.duration=1e14"}), Contains("key 'run.duration'") && Contains("[0, 1e12]"));
    CHECK_THAT(scene_error(f, {"run.duration=1e11"}),
               Contains("key 'run.duration'") && Contains("steps") && Contains("Fix: at most 1e15 steps"));
    CHECK_THAT(scene_error(f, {"run.dt=1e-320", "run.allow_unstable_dt=true"}),
               Contains("key 'run.dt'") && Contains("below the smallest normal double"));
  }
  SECTION("an acceleration past any centrifuge, and fills that place nothing") {
    // Both were found by the input fuzzer: gravity 1e308 m/s^2 passed check and moved every grain
    // through a wall in the first step ("reduce run.dt"); a fill of zero grains was refused
    // without a line.
    const fs::path f = dir.write("g.toml", kScene);
    CHECK_THAT(scene_error(f, {"run.gravity=[1e308,1e308,1e308]"}),
               Contains("key 'run.gravity'") && Contains("more than the 200 g") && Contains("Fix:"));
    // A drum turning 1e9 rad/s moved its wall 750 m per step, a radius of 1e308 overflowed the
    // series' arrays: both refused at their keys.
    const fs::path drum = fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/drum_seed000_settled.toml";
    CHECK_THAT(scene_error(drum, {"wall.0.omega=1e9"}),
               Contains("key 'wall[0].omega'") && Contains("m per step, more than 0.1 of the smallest diameter"));
    CHECK_THAT(scene_error(drum, {"wall.0.radius=1e308"}), Contains("key 'wall[0].radius'") && Contains("1000"));
    const std::string none = with(kScene, "count = { glass = 50 }", "count = { glass = 0 }");
    CHECK_THAT(scene_error(dir.write("none.toml", none), {}, true),
               Contains(at(dir.path / "none.toml", line_of(none, "[[fill]]"))) && Contains("place no grains") &&
                   Contains("Fix:"));
  }
  SECTION("a skin larger than the smallest grain") {
    // A 1 m skin around 1 mm grains listed every pair of a 47,108-grain drum: a billion pairs, until
    // the machine ran out of memory.
    // The memory estimate counts the pairs the skin lists, so the scene is refused before anything
    // is allocated (with the memory this test lets a scene plan for lowered to 64 MB, as a small
    // machine's).
    gf::memory_limit().store(std::size_t(64) << 20);
    // 50 grains list at most 49 partners each, whatever the skin: accepted.
    const std::string few = scene_error(dir.write("skin.toml", kScene), {"run.skin=1"}, true);
    // 2,000 grains in a 1 m box with a 1 m skin: 2 million pairs, 0.2 GB of list.
    const std::string many = scene_error(
        dir.write("skin_many.toml", with(kScene, "count = { glass = 50 }", "count = { glass = 2000 }")),
        {"run.skin=1", "wall.0.hi=[1,1,1]", "fill.0.region.hi=[0.99,0.99,0.99]"}, true);
    gf::memory_limit().store(0);
    CHECK(few.empty());
    CHECK_THAT(many, Contains("1999 neighbour pairs per grain with run.skin = 1 m") && Contains("Fix:"));
  }
  SECTION("long text from the user is shown cut") {
    // A 100 kB value, key or --set argument once made a 100 kB message.
    const std::string huge(100000, 'q');
    const fs::path f = dir.write("long.toml", with(kScene, "model = \"linear_spring_dashpot\"",
                                                   "model = \"" + huge + "\""));
    std::string e = scene_error(f);
    CHECK(e.size() < 1000);
    CHECK_THAT(e, Contains("key 'contact.model'") && Contains("...' is not an accepted value"));
    e = scene_error(dir.write("long_key.toml", with(kScene, "skin = 1.0e-4\n", "skin = 1.0e-4\n" + huge + " = 3\n")));
    CHECK(e.size() < 1000);
    CHECK_THAT(e, Contains("unknown key 'qqq") && Contains("...'"));
    e = scene_error(dir.write("ok_long.toml", kScene), {"run." + huge + "=1"});
    CHECK(e.size() < 1000);
    CHECK_THAT(e, Contains("command line (--set run.qqq") && Contains("Fix:"));
    // A state file's path of 100 kB: once echoed whole (a 2 MB path made a 2 MB line); its end is kept.
    const std::string long_path = kScene.substr(0, kScene.find("[[fill]]")) + "[[fill]]\nkind = \"file\"\npath = \"" +
                                  huge + "/grains.csv\"\ntypes = { 1 = \"glass\" }\n\n" + kScene.substr(kScene.find("[output]"));
    e = scene_error(dir.write("long_path.toml", long_path), {}, true);
    CHECK(e.size() < 1000);
    CHECK_THAT(e, Contains("...qqq") && Contains("/grains.csv") && Contains("Fix:"));
  }
  SECTION("output intervals shorter than the time step") {
    // A checkpoint interval below run.dt once wrote a checkpoint every step, and with
    // checkpoint_keep_all a file per step without bound; the series and frames were refused already.
    const fs::path f = dir.write("intervals.toml", kScene);
    for (const char* key : {"series_interval", "frame_interval", "checkpoint_interval"})
      CHECK_THAT(scene_error(f, {std::string("output.") + key + "=1e-9"}),
                 Contains(std::string("key 'output.") + key + "'") && Contains("shorter than the time step") &&
                     Contains("Fix:"));
    CHECK(scene_error(f, {"output.checkpoint_interval=0"}, true).empty());
  }
  SECTION("a unit slip is named as the likely mistake, before the time step or the fill") {
    const fs::path f = dir.write("units.toml", kScene);
    // g/cm^3 for kg/m^3: once "set dt <= 1.06e-6", as if the step were wrong.
    CHECK_THAT(scene_error(f, {"species.0.density=2.5"}),
               Contains("key 'species[0].density'") && Contains("is it in g/cm³? 2.5 g/cm³ is 2500 kg/m³"));
    // mm/s^2 for m/s^2: once accepted.
    CHECK_THAT(scene_error(f, {"run.gravity=[0,-9810,0]"}),
               Contains("key 'run.gravity'") && Contains("1000 g") && Contains("is it in mm/s^2?"));
    // A diameter in mm: once "could not place grain 1 ... lower the count".
    const std::string mm = with(kScene, "diameter = 2.0e-3", "diameter = 2.0");
    const fs::path fm = dir.write("mm.toml", mm);
    CHECK_THAT(scene_error(fm),
               Contains(at(fm, line_of(mm, "diameter = 2.0")) + " key 'species[0].diameter'") &&
                   Contains("wider than fill[0]'s region") && Contains("is the diameter in millimetres?"));
    // A denormal passed the interval (0, 1e6] and the run then "blew up".
    CHECK_THAT(scene_error(f, {"species.0.density=1e-320"}),
               Contains("key 'species[0].density'") && Contains("below the smallest normal double"));
    CHECK_THAT(scene_error(f, {"contact.kn=1e-320"}), Contains("key 'contact.kn'") && Contains("Fix:"));
    // A drum radius in mm: once "lower omega or run.dt"; now the radius is named.
    const fs::path drum = fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/drum_quick.toml";
    CHECK_THAT(scene_error(drum, {"wall.0.radius=40"}),
               Contains("key 'wall[0].radius'") && Contains("is the radius in millimetres? 40 mm is 0.04 m"));
    CHECK_THAT(scene_error(drum, {"wall.0.omega=1e4"}),
               Contains("key 'wall[0].omega'") && Contains("Fix: lower omega"));
  }
  SECTION("a misspelt required key is reported as unknown, not as missing") {
    const std::string text = with(kScene, "friction = ", "fricton = ");
    const fs::path f = dir.write("fricton.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "fricton = ")) + " key 'contact.fricton'"));
    CHECK_THAT(e, Contains("unknown key 'fricton'") && Contains("did you mean 'friction'?"));
  }
  SECTION("a value given on the command line is located there") {
    const fs::path f = dir.write("ok.toml", kScene);
    CHECK_THAT(scene_error(f, {"run.skin=-1"}),
               Contains("command line (--set run.skin=-1): key 'run.skin'") && Contains("out of range"));
  }
}

TEST_CASE("dem scene: picture keys are checked before anything runs", "[dem_scene][picture]") {
  TempDir dir("dem_scene_pictures");
  SECTION("pictures of a scene without a drum") {
    const std::string text =
        with(kScene, "frame_interval = 5.0e-4\n", "frame_interval = 5.0e-4\npicture_angles = [2.0]\n");
    const fs::path f = dir.write("no_drum.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "picture_angles")) + " key 'output.picture_angles'"));
    CHECK_THAT(e, Contains("need a drum"));
  }
  SECTION("an unknown colouring") {
    const std::string text =
        with(kScene, "frame_interval = 5.0e-4\n", "frame_interval = 5.0e-4\npicture_colour = \"size\"\n");
    const fs::path f = dir.write("colour.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(at(f, line_of(text, "picture_colour")) + " key 'output.picture_colour'"));
    CHECK_THAT(e, Contains("species") && Contains("speed"));
  }
  SECTION("a size out of range") {
    const std::string text = with(kScene, "frame_interval = 5.0e-4\n", "frame_interval = 5.0e-4\npicture_size = 4\n");
    const fs::path f = dir.write("size.toml", text);
    CHECK_THAT(scene_error(f), Contains(at(f, line_of(text, "picture_size")) + " key 'output.picture_size'"));
  }
  SECTION("two angles that would share a file name") {
    const fs::path f = dir.write("ok.toml", kScene);
    const std::string e = scene_error(f, {"output.picture_angles=[1.0, 1.001]"});
    CHECK_THAT(e, Contains("key 'output.picture_angles'") && Contains("angle_01.00.png"));
  }
  SECTION("an angle that would share a file name with the interval's") {
    const fs::path f = dir.write("ok.toml", kScene);
    const std::string e = scene_error(f, {"output.picture_angles=[0.5, 1.001]", "output.picture_interval=0.5"});
    CHECK_THAT(e, Contains("key 'output.picture_angles'") && Contains("angle_01.00.png"));
  }
}

TEST_CASE("dem scene: a time step above the critical step is refused unless allowed", "[dem_scene]") {
  TempDir dir("dem_scene_dt");
  const double limit = 0.1 * expected_critical_period();  // dt_safety defaults to 0.1
  const std::string text = with(kScene, "dt = 1.0e-5", "dt = 1.0e-4");
  const fs::path f = dir.write("big_dt.toml", text);
  const std::string e = scene_error(f);
  CHECK_THAT(e, Contains(at(f, line_of(text, "dt = 1.0e-4")) + " key 'run.dt'"));
  CHECK_THAT(e, Contains("tangential, glass-glass"));  // the term that sets the limit
  // The limit is printed to 4 significant digits: 5e-4 relative covers the rounding.
  CHECK(number_after(e, "the limit is ") == Approx(limit).epsilon(5e-4));
  CHECK(number_after(e, "set dt <= ") == Approx(limit).epsilon(5e-4));
  CHECK_THAT(e, Contains("allow_unstable_dt = true"));  // the fix names the escape hatch

  SECTION("allowed in the file") {
    const fs::path g = dir.write("big_dt_allowed.toml",
                                 with(text, "skin = 1.0e-4\n", "skin = 1.0e-4\nallow_unstable_dt = true\n"));
    CHECK(scene_error(g, {}, true).empty());
    CHECK(gf::load_dem_scene(gf::SceneDoc::load(g)).allow_unstable_dt);
  }
  SECTION("allowed from the command line") {
    CHECK(scene_error(f, {"run.allow_unstable_dt=true"}, true).empty());
    CHECK(gf::load_dem_scene(gf::SceneDoc::load(f, {"run.allow_unstable_dt=true"})).dt == 1.0e-4);
  }
  SECTION("the check applies to a dt set on the command line") {
    const fs::path ok = dir.write("ok.toml", kScene);
    CHECK_THAT(scene_error(ok, {"run.dt=1e-4"}), Contains("command line (--set run.dt=1e-4): key 'run.dt'"));
  }
  SECTION("just below the limit is accepted") {
    const fs::path ok = dir.write("ok.toml", kScene);
    std::ostringstream set;
    set.precision(17);
    set << "run.dt=" << 0.999 * limit;
    CHECK(scene_error(ok, {set.str()}).empty());
  }
}

TEST_CASE("dem scene: fills that cannot be made name the scene file and the fill", "[dem_scene]") {
  TempDir dir("dem_scene_fill");
  SECTION("more grains than the region holds") {
    // 5000 spheres of 2 mm in 1.15 cm^3 would be 18 times the region's volume.
    const std::string text = with(kScene, "count = { glass = 50 }", "count = { glass = 5000 }");
    const fs::path f = dir.write("crowded.toml", text);
    CHECK(scene_error(f).empty());  // valid as text ...
    const std::string e = scene_error(f, {}, true);  // ... but cannot be placed
    CHECK_THAT(e, Contains(at(f, line_of(text, "[[fill]]")) + " fill[0]:"));
    CHECK_THAT(e, Contains("could not place"));
  }
  SECTION("a region reaching through a wall") {
    const std::string text = with(kScene, "lo = [0.001, 0.001, 0.001]", "lo = [-0.002, 0.001, 0.001]");
    const fs::path f = dir.write("through.toml", text);
    const std::string e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, line_of(text, "[[fill]]")) + " fill[0]:"));
    CHECK_THAT(e, Contains("reaches through wall 'box-x'"));
  }
  SECTION("no fill at all") {
    const std::string text = kScene.substr(0, kScene.find("[[fill]]")) + kScene.substr(kScene.find("[output]"));
    const fs::path f = dir.write("empty.toml", text);
    const std::string e = scene_error(f);
    CHECK_THAT(e, Contains(f.string() + ":") && Contains("key 'fill'") && Contains("places no grains"));
  }
  SECTION("a state file") {
    // Read relative to the scene file's folder, as a scene run from elsewhere would.
    const std::string file_fill =
        "[[fill]]\nkind = \"file\"\npath = \"grains.csv\"\ntypes = { 1 = \"glass\" }\n\n";
    const std::string text =
        kScene.substr(0, kScene.find("[[fill]]")) + file_fill + kScene.substr(kScene.find("[output]"));
    const fs::path f = dir.write("from_file.toml", text);
    const fs::path csv = dir.path / "grains.csv";
    const int fill_line = line_of(text, "[[fill]]");

    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,1,0.002,0.006,0.003,0.003\n");
    CHECK(scene_error(f, {}, true).empty());

    // Velocities and spins, when the file has them, start the grains moving (a flowing state).
    dir.write("grains.csv", "id,type,diameter,x,y,z,vx,vy,vz,wx,wy,wz\n1,1,0.002,0.003,0.003,0.003,0.1,-0.2,0.3,4,5,6\n"
                            "2,1,0.002,0.006,0.003,0.003,0,0,0,0,0,0\n");
    {
      auto moving = gf::DemSimulation::from_file(f);
      const gf::Grains& g = moving.grains();
      CHECK((g.vel.x[0] == 0.1 && g.vel.y[0] == -0.2 && g.vel.z[0] == 0.3));
      CHECK((g.omega.x[0] == 4.0 && g.omega.y[0] == 5.0 && g.omega.z[0] == 6.0));
      CHECK((g.vel.x[1] == 0.0 && g.omega.z[1] == 0.0));
    }

    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,2,0.002,0.006,0.003,0.003\n");
    std::string e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " fill[0]:"));
    CHECK_THAT(e, Contains(csv.string() + ":3: type 2 is not mapped to a species"));

    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,1,0.003,0.006,0.003,0.003\n");
    e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " fill[0]:"));
    CHECK_THAT(e, Contains(csv.string() + ":3: diameter 0.003 m does not match species 'glass' (0.002 m)"));

    // A centre behind a wall: outside the domain (it was reported as an instability once running).
    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,1,0.002,0.006,0.003,100\n");
    e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " fill[0]:") &&
                      Contains(csv.string() + ":3: the grain's centre (0.006, 0.003, 100) m is outside wall 'box+z'"));

    // The same file in two fills: every grain twice, one on the other.
    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,1,0.002,0.006,0.003,0.003\n");
    const std::string twice = kScene.substr(0, kScene.find("[[fill]]")) + file_fill + file_fill +
                              kScene.substr(kScene.find("[output]"));
    e = scene_error(dir.write("twice.toml", twice), {}, true);
    // Named by the file's lines, not by rows counted over the fills.
    CHECK_THAT(e, Contains("the grain at line 2 of " + csv.string() + " and the grain at line 2 of " + csv.string()) &&
                      Contains("one on the other") && Contains("Fix:"));

    // Two files giving one id: refused with both lines (ids from state files are kept).
    dir.write("other.csv", "id,type,diameter,x,y,z\n7,1,0.002,0.003,0.006,0.003\n2,1,0.002,0.006,0.006,0.003\n");
    std::string other_fill = file_fill;
    other_fill.replace(other_fill.find("grains.csv"), 10, "other.csv");
    const std::string two = kScene.substr(0, kScene.find("[[fill]]")) + file_fill + other_fill +
                            kScene.substr(kScene.find("[output]"));
    e = scene_error(dir.write("two.toml", two), {}, true);
    CHECK_THAT(e, Contains("id 2 is given to the grain at line 3 of " + csv.string()) &&
                      Contains("line 3 of " + (dir.path / "other.csv").string()) && Contains("Fix:"));

    // Kept: the file's ids (7 and 2), and a random fill's grains numbered on from past the largest.
    const std::string mixed =
        kScene.substr(0, kScene.find("[[fill]]")) + other_fill + kScene.substr(kScene.find("[[fill]]"));
    gf::DemSimulation sim(gf::load_dem_scene(gf::SceneDoc::load(dir.write("mixed.toml", mixed))));
    const gf::Grains& g = sim.grains();
    std::vector<std::int64_t> ids(g.n_owned);
    for (std::size_t i = 0; i < g.n_owned; ++i) ids[i] = g.pid.id[i];
    std::sort(ids.begin(), ids.end());
    REQUIRE(ids.size() == 52);
    CHECK(ids[0] == 2);
    CHECK(ids[1] == 7);
    for (std::size_t i = 2; i < ids.size(); ++i) CHECK(ids[i] == static_cast<std::int64_t>(6 + i));
    CHECK(g.next_id == 58);

    // Two grains half a diameter into each other: no step has been taken, so the input is at fault
    // (it was reported as an instability with "reduce run.dt"); check refuses it as run does.
    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n2,1,0.002,0.004,0.003,0.003\n");
    e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " the fills' initial state: grain id ") &&
                      Contains("in the initial state") && Contains("Fix: place the grains apart"));
    const Exit overlapping = run_cli(dir, "check " + quote(f.string()));
    CHECK(overlapping.code == 1);
    CHECK_THAT(overlapping.err, Contains("the fills' initial state"));

    dir.write("grains.csv", "id,type,diameter,x,y,z\n");  // the header alone: no grains
    e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " fill[0]:") && Contains("holds no grains") && Contains("Fix:"));
    // `check` builds the fills as `run` does, so it refuses the same file (exit status 1).
    const Exit c = run_cli(dir, "check " + quote(f.string()));
    CHECK(c.code == 1);
    CHECK_THAT(c.err, Contains("holds no grains"));

    fs::remove(csv);
    e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(at(f, fill_line) + " fill[0]:") && Contains("grains.csv"));

    // A NUL in the path once cut it short there, so "grains.csv\u0000x" read grains.csv: refused.
    dir.write("grains.csv", "id,type,diameter,x,y,z\n1,1,0.002,0.003,0.003,0.003\n");
    const fs::path nul = dir.write("nul.toml", with(text, "path = \"grains.csv\"", "path = \"grains.csv\\u0000x\""));
    e = scene_error(nul, {}, true);
    CHECK_THAT(e, Contains(at(nul, fill_line + 2) + " key 'fill[0].path'") && Contains("NUL") && Contains("Fix:"));
    // Control characters in an echoed value are written \xNN, so the message is printed whole.
    e = scene_error(f, {"contact.model=\"a\\u0007b\\u001b[31m\""});
    CHECK_THAT(e, Contains("'a\\x07b\\x1b[31m' is not an accepted value"));
  }
  SECTION("more grains than the machine's memory holds") {
    // Ten fills of 1e8 grains (the most one count may give) need about 800 GiB of arrays: refused,
    // by check too, before anything is allocated, at the fill asking for the most (the last of ties).
    const std::string fill = kScene.substr(kScene.find("[[fill]]"), kScene.find("[output]") - kScene.find("[[fill]]"));
    std::string fills;
    for (int k = 0; k < 10; ++k) fills += with(fill, "count = { glass = 50 }", "count = { glass = 100000000 }");
    const std::string text = kScene.substr(0, kScene.find("[[fill]]")) + fills + kScene.substr(kScene.find("[output]"));
    const fs::path f = dir.write("huge.toml", text);
    const std::string e = scene_error(f, {}, true);
    CHECK_THAT(e, Contains(" fill[9]:") && Contains("1000000000 grains") && Contains("GiB") && Contains("Fix:"));
    const Exit c = run_cli(dir, "check " + quote(f.string()));
    CHECK(c.code == 1);
    CHECK_THAT(c.err, Contains("GiB"));
  }
}

// ---------------------------------------------------------------------------------------------------------------------
TEST_CASE("cli: run writes the series, the frames and the summary", "[dem_scene][cli]") {
  REQUIRE(fs::exists(GRAINFLOW_BINARY));
  TempDir dir("cli_run");
  const fs::path scene = dir.write("tiny.toml", kScene);
  const fs::path out = dir.path / "out";
  const Exit e = run_cli(dir, "run " + quote(scene.string()) + " --out " + quote(out.string()) +
                                  " --steps 200 --threads 1 --quiet");
  INFO("stderr: " << e.err);
  REQUIRE(e.exited);
  REQUIRE(e.code == 0);

  // series.csv: the header and a row every 1e-4 s = 10 steps, from t = 0 to t = 200 dt.
  const auto rows = read_lines(out / "series.csv");
  REQUIRE(rows.size() == 1 + 21);
  CHECK(rows[0] == kSeriesHeader);
  for (std::size_t k = 1; k < rows.size(); ++k) {
    INFO("row " << k << ": " << rows[k]);
    const auto v = fields(rows[k]);
    REQUIRE(v.size() == 8);
    // Times are k * 10 dt computed as a product, not a running sum: 1e-15 s absorbs the rounding.
    CHECK(std::abs(v[0] - static_cast<double>(k - 1) * 1.0e-4) < 1e-15);
  }

  // Frames every 5e-4 s: t = 0, 5e-4, ..., 2e-3, each listed in frames.pvd and present on disk.
  const std::string pvd = read_file(out / "frames.pvd");
  CHECK_THAT(pvd, Contains("</VTKFile>"));
  std::size_t listed = 0;
  for (std::size_t p = pvd.find("file=\""); p != std::string::npos; p = pvd.find("file=\"", p + 1)) {
    const auto b = p + 6, q = pvd.find('"', b);
    const fs::path frame = out / pvd.substr(b, q - b);
    INFO(frame);
    CHECK(fs::exists(frame));
    CHECK(read_file(frame).find("<VTKFile type=\"PolyData\"") != std::string::npos);
    ++listed;
  }
  CHECK(listed == 5);
  std::size_t vtp = 0;
  for (const auto& entry : fs::directory_iterator(out / "frames")) vtp += entry.path().extension() == ".vtp";
  CHECK(vtp == 5);

  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  CHECK(summary.at("status") == "completed");
  CHECK(summary.at("steps") == 200);
  CHECK(summary.at("grains") == 50);
  CHECK(summary.at("particle_steps_per_second").get<double>() > 0.0);
  CHECK(summary.at("critical_term") == "tangential, glass-glass");
  // The build's commit, and the scene as read: the file's keys, and the defaults the readers took.
  CHECK(!summary.at("commit").get<std::string>().empty());
  const auto& read_scene = summary.at("scene_resolved");
  CHECK(read_scene.at("run").at("dt") == 1.0e-5);                            // from the file
  CHECK(read_scene.at("run").at("dt_safety") == 0.1);                        // a default
  CHECK(read_scene.at("contact").at("model") == "linear_spring_dashpot");
  CHECK(summary.at("counts").at("grains_at_start") == 50);
  std::map<std::string, std::int64_t> calls;
  for (const auto& t : summary.at("time_per_system")) {
    calls[t.at("system").get<std::string>()] = t.at("calls").get<std::int64_t>();
    CHECK(t.at("seconds").get<double>() >= 0.0);
  }
  for (const char* s : {"integrate_positions", "broadphase", "pair_contact", "wall_contact", "integrate_velocities"}) {
    INFO(s);
    CHECK(calls[s] == 200);  // once per step
  }
  CHECK(calls.count("series_output") == 1);
  CHECK(calls.count("frame_output") == 1);
  CHECK(fs::exists(out / "final_state.csv"));
}

TEST_CASE("cli: check prints the systems and the critical step", "[dem_scene][cli]") {
  TempDir dir("cli_check");
  const fs::path scene = dir.write("tiny.toml", kScene);
  const Exit e = run_cli(dir, "check " + quote(scene.string()));
  INFO("stdout: " << e.out << "\nstderr: " << e.err);
  REQUIRE(e.exited);
  REQUIRE(e.code == 0);
  CHECK_THAT(e.out, Contains("valid"));
  for (const char* s : {"integrate_positions", "broadphase", "pair_contact", "wall_contact", "integrate_velocities"})
    CHECK_THAT(e.out, Contains(s));
  CHECK_THAT(e.out, Contains("critical step"));
  CHECK_THAT(e.out, Contains("tangential, glass-glass"));
  // Printed to 4 significant digits: 5e-4 relative.
  CHECK(number_after(e.out, "smallest time-step term ") == Approx(expected_critical_period()).epsilon(5e-4));
  CHECK(e.err.empty());
}

TEST_CASE("cli: the README's default scene is valid, and a run names the picture it ends with", "[dem_scene][cli]") {
  TempDir dir("cli_default");
  const std::string scene = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/drum_quick.toml";
  CHECK(run_cli(dir, "check " + quote(scene)).code == 0);
  // Cut short (a few settling steps, 20 turning steps): the picture at 0 rad is the last one drawn.
  const fs::path out = dir.path / "out";
  const Exit e = run_cli(dir, "run " + quote(scene) + " --out " + quote(out.string()) +
                                  " --steps 20 --quiet --set settle.time=0.003");
  INFO(e.err);
  REQUIRE(e.code == 0);
  const auto lines = gf::test::lines_of(e.err);
  REQUIRE_FALSE(lines.empty());
  CHECK(lines.back() == "grainflow: picture of the drum: " + (out / "pictures" / "angle_00.00.png").string());
  CHECK(fs::exists(out / "pictures" / "angle_00.00.png"));
}

TEST_CASE("cli: a bad scene and a bad flag fail cleanly", "[dem_scene][cli]") {
  TempDir dir("cli_bad");
  SECTION("bad scene: exit 1, file:line on stderr") {
    const std::string text = with(kScene, "skin = 1.0e-4\n", "skin = 1.0e-4\nseeed = 3\n");
    const fs::path scene = dir.write("bad.toml", text);
    const Exit e = run_cli(dir, "run " + quote(scene.string()) + " --out " + quote((dir.path / "out").string()) +
                                    " --steps 10 --quiet");
    REQUIRE(e.exited);  // an error, not a crash
    CHECK(e.code == 1);
    CHECK_THAT(e.err, Contains(at(scene, line_of(text, "seeed")) + " key 'run.seeed'"));
    CHECK_FALSE(fs::exists(dir.path / "out" / "summary.json"));  // nothing ran
  }
  SECTION("bad scene under check") {
    const fs::path scene = dir.write("bad.toml", with(kScene, "dt = 1.0e-5", "dt = 1.0e-4"));
    const Exit e = run_cli(dir, "check " + quote(scene.string()));
    REQUIRE(e.exited);
    CHECK(e.code == 1);
    CHECK_THAT(e.err, Contains("key 'run.dt'"));
  }
  SECTION("missing scene file") {
    const Exit e = run_cli(dir, "check " + quote((dir.path / "nope.toml").string()));
    REQUIRE(e.exited);
    CHECK(e.code == 1);
    CHECK_THAT(e.err, Contains("nope.toml") && Contains("does not exist"));
  }
  SECTION("unknown flag: exit 2 with usage") {
    const fs::path scene = dir.write("tiny.toml", kScene);
    const Exit e = run_cli(dir, "run " + quote(scene.string()) + " --bogus");
    REQUIRE(e.exited);
    CHECK(e.code == 2);
    CHECK_THAT(e.err, Contains("--bogus") && Contains("usage:"));
  }
  SECTION("bad flag value: exit 2 with usage") {
    const fs::path scene = dir.write("tiny.toml", kScene);
    const Exit e = run_cli(dir, "run " + quote(scene.string()) + " --threads zero");
    REQUIRE(e.exited);
    CHECK(e.code == 2);
    CHECK_THAT(e.err, Contains("--threads") && Contains("usage:"));
  }
  SECTION("a thread count past the bound: exit 2 naming the bound") {
    const fs::path scene = dir.write("tiny.toml", kScene);
    const Exit e = run_cli(dir, "run " + quote(scene.string()) + " --threads 100000");
    REQUIRE(e.exited);
    CHECK(e.code == 2);
    CHECK_THAT(e.err, Contains("--threads needs an integer from 1 to 1024, got '100000'"));
  }
  SECTION("--help and --version: exit 0 on stdout") {
    for (const char* args : {"--help", "-h", "run --help", "check x.toml --help"}) {
      const Exit e = run_cli(dir, args);
      INFO(args);
      CHECK(e.code == 0);
      CHECK_THAT(e.out, Contains("usage:") && Contains("grainflow run SCENE"));
    }
    const Exit v = run_cli(dir, "--version");
    CHECK(v.code == 0);
    CHECK_THAT(v.out, Contains("grainflow 0."));
  }
  SECTION("no arguments: exit 2 with usage") {
    const Exit e = run_cli(dir, "");
    REQUIRE(e.exited);
    CHECK(e.code == 2);
    CHECK_THAT(e.err, Contains("usage:"));
  }
}

TEST_CASE("cli: SIGTERM stops a run after the step in flight and keeps its results", "[dem_scene][cli]") {
  REQUIRE(fs::exists(GRAINFLOW_BINARY));
  TempDir dir("cli_sigterm");
  const fs::path scene = dir.write("tiny.toml", kScene);
  const fs::path out = dir.path / "out";
  const fs::path series = out / "series.csv";
  const std::int64_t requested = 1'000'000'000;  // far more than runs before the signal

  const std::string log = (dir.path / "stderr.txt").string();
  const pid_t pid = gf::test::spawn_cli({"run", scene.string(), "--out", out.string(), "--steps",
                                         std::to_string(requested), "--threads", "1", "--quiet", "--set",
                                         "output.frame_interval=0.01"},
                                        log);
  REQUIRE(pid >= 0);

  // Wait (at most 60 s) until the run has written 30 rows, then stop it.
  const auto t0 = std::chrono::steady_clock::now();
  auto waited = [&] { return std::chrono::steady_clock::now() - t0 > std::chrono::seconds(60); };
  std::string before;
  int status = 0;
  bool exited_early = false;
  for (;;) {
    before = fs::exists(series) ? read_file(series) : "";
    if (std::count(before.begin(), before.end(), '\n') >= 31) break;
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      exited_early = true;
      break;
    }
    if (waited()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (exited_early) FAIL("the run ended before it was signalled: " << read_file(log));
  REQUIRE(::kill(pid, SIGTERM) == 0);
  bool done = false;
  for (int k = 0; k < 3000 && !done; ++k) {  // up to 30 s for the step in flight and the final writes
    done = ::waitpid(pid, &status, WNOHANG) == pid;
    if (!done) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (!done) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
    FAIL("grainflow did not stop within 30 s of SIGTERM");
  }
  const std::string err = read_file(log);
  INFO("stderr: " << err);
  REQUIRE(WIFEXITED(status));  // it stopped itself, it was not killed by the signal
  CHECK(WEXITSTATUS(status) == 128 + SIGTERM);  // the status of a stop by SIGTERM, its results kept
  CHECK_THAT(err, Contains("interrupted after"));

  const auto summary = nlohmann::json::parse(read_file(out / "summary.json"));
  CHECK(summary.at("status") == "interrupted");
  const std::int64_t steps_done = summary.at("steps").get<std::int64_t>();
  // At least the 30 rows seen before the signal: t = 0 and every 10 steps to step 290 (the header is
  // the 31st line). A slow build (the sanitizers) can stop right there.
  CHECK(steps_done >= 290);
  CHECK(steps_done < requested);

  // Every row written before the signal is still there, unchanged, and every row is complete.
  const std::string after = read_file(series);
  const std::string complete_before = before.substr(0, before.rfind('\n') + 1);
  CHECK(after.compare(0, complete_before.size(), complete_before) == 0);
  REQUIRE(!after.empty());
  CHECK(after.back() == '\n');
  const auto rows = lines_of(after);
  REQUIRE(rows.size() >= 32);
  CHECK(rows[0] == kSeriesHeader);
  // Rows on the sampling grid (every 10 steps) up to the last step, then one for the final state if
  // the run stopped between samples.
  const std::size_t on_grid = static_cast<std::size_t>(steps_done / 10) + 1;
  const std::size_t expected_rows = on_grid + (steps_done % 10 != 0 ? 1 : 0);
  CHECK(rows.size() - 1 == expected_rows);
  double last_time = -1;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    INFO("row " << k << ": " << rows[k]);
    const auto v = fields(rows[k]);
    REQUIRE(v.size() == 8);
    CHECK(v[0] > last_time);
    // Times are products k * dt: rounding of a few ulp of ~1 s, far below 1e-12 s.
    if (k <= on_grid) CHECK(std::abs(v[0] - static_cast<double>(k - 1) * 1.0e-4) < 1e-12);
    last_time = v[0];
  }
  // The last row is the state the summary reports.
  CHECK(last_time == summary.at("simulated_time").get<double>());

  const std::string pvd = read_file(out / "frames.pvd");
  CHECK_THAT(pvd, Contains("</VTKFile>"));
  CHECK(fs::exists(out / "final_state.csv"));
}

TEST_CASE("scene: the step holds only what the scene needs", "[scene]") {
  // Walls and rotation each add systems or columns; a scene without them has neither.
  const std::string base = gf::test::binary_box_scene(200, 10, 9.81);
  const std::string no_walls = base.substr(0, base.find("[[wall]]")) + base.substr(base.find("[[fill]]"));
  std::string still = no_walls;
  for (std::size_t at = still.find("density = 2500.0\n"); at != std::string::npos;
       at = still.find("density = 2500.0\n", at + 1))
    still.insert(at + 17, "rotates = false\n");
  auto names = [](gf::DemSimulation& s) { return s.step().names(); };
  auto has = [](const std::vector<std::string>& v, const char* n) { return std::find(v.begin(), v.end(), n) != v.end(); };

  gf::DemSimulation full = gf::DemSimulation::from_text(base);
  CHECK(has(names(full), "wall_contact"));
  CHECK(full.grains().omega.x.size() == full.grains().n);

  gf::DemSimulation open = gf::DemSimulation::from_text(no_walls);
  CHECK_FALSE(has(names(open), "wall_contact"));
  CHECK(has(names(open), "pair_contact"));

  gf::DemSimulation translating = gf::DemSimulation::from_text(still);
  CHECK_FALSE(translating.grains().spin);
  CHECK(translating.grains().omega.x.size() == 0);
  // 9 columns fewer (angular velocity, torque, wall torque) of 8 bytes per grain.
  CHECK(open.grains().bytes() - translating.grains().bytes() >= 9 * 8 * translating.grains().n);
  // Stirred, the grains collide: pair contacts without spin, the list rebuilt as they move.
  gf::test::stir_by_id(translating.grains(), 3, 0.3);
  std::size_t contacts = 0;
  for (int k = 0; k < 300; ++k) {
    translating.advance(1);
    contacts = std::max(contacts, translating.world().resources.get<gf::PairForces>().contacts());
  }
  CHECK(contacts > 0);
  CHECK(translating.world().resources.get<gf::BroadphaseState>().rebuilds > 1);
}
