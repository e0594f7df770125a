// Continuous operation through the command line ([[feed]] and [[outlet]] of a scene, systems/flow/):
// grains fed into an empty domain fall freely to an outlet, so each one's residence time has a
// closed form; mass is conserved between feed, hold-up and outlet; a run in two pieces writes the
// same files as one run; bad feed tables are refused with the fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gf::test::quote;
using gf::test::read_file;
using gf::test::read_lines;
using gf::test::run_cli;
using gf::test::TempDir;

namespace {

constexpr double kG = 9.81;            // m/s^2
constexpr double kV0 = 0.5;            // m/s, downwards, of a fed grain
constexpr double kDt = 2.0e-5;         // s
constexpr double kOutletEvery = 1e-3;  // s

// Two species fed 50/50 by mass at 10 g/s into a 3.2 mm slab at y = 0.100 .. 0.1032 m, moving down
// at 0.5 m/s, so each event's grains have left the slab before the next event (10 ms, 5.5 mm) and
// no grain ever meets another: they fall freely to the outlet below y = 0. No walls, no fill.
std::string free_fall_scene(const std::string& duration = "0.3") {
  return "[run]\ndt = 2.0e-5\nduration = " + duration +
         "\nskin = 2.0e-4\ngravity = [0.0, -9.81, 0.0]\nseed = 3\n"
         "[[species]]\nname = \"a\"\ndiameter = 2.0e-3\ndensity = 2500.0\n"
         "[[species]]\nname = \"b\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\nen = 0.3\net = 0.3\n"
         "er = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
         "[[feed]]\nmass_rate = 0.01\nfractions = { a = 0.5, b = 0.5 }\nvelocity = [0.0, -0.5, 0.0]\ninterval = 0.01\n"
         "region = { shape = \"box\", lo = [-0.02, 0.1, -0.02], hi = [0.02, 0.1032, 0.02] }\n"
         "[[outlet]]\ninterval = 0.001\nregion = { shape = \"box\", lo = [-1.0, -1.0, -1.0], hi = [1.0, 0.0, 1.0] }\n"
         "[output]\nseries_interval = 0.01\n"
         // Layers across the fall, sampled off the checkpoint grid and pooled in threes, so that a
         // checkpoint falls inside a pool.
         "[analysis]\nspecies = \"a\"\n[analysis.layers]\ninlet = [0.0, 0.1, 0.0]\naxis = [0.0, -1.0, 0.0]\n"
         "distances = [0.02, 0.05]\ncell = 0.01\nmin_grains = 1\ninterval = 0.007\npool = 3\n";
}

// Time for a grain starting at height y0 with speed kV0 downwards to fall to y = 0.
double fall_time(double y0) { return (-kV0 + std::sqrt(kV0 * kV0 + 2.0 * kG * y0)) / kG; }

std::vector<std::vector<double>> csv_rows(const fs::path& file) {
  std::vector<std::vector<double>> rows;
  const auto lines = read_lines(file);
  for (std::size_t k = 1; k < lines.size(); ++k) {
    std::vector<double> row;
    std::stringstream ss(lines[k]);
    std::string cell;
    while (std::getline(ss, cell, ',')) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  return rows;
}

std::string args(const fs::path& scene, const fs::path& out, const std::string& more = "") {
  return "run " + quote(scene.string()) + " --out " + quote(out.string()) + " --threads 2 --quiet " + more;
}

}  // namespace

TEST_CASE("flow: fed grains falling freely to an outlet leave after the closed-form fall time", "[flow][cli]") {
  TempDir dir("flow_fall");
  const fs::path scene = dir.write("fall.toml", free_fall_scene());
  auto r = run_cli(dir, args(scene, dir.path / "run"));
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto rows = csv_rows(dir.path / "run" / "residence.csv");
  // Events at 0, 0.01, ..., 0.19 s have reached the outlet by 0.3 s (each falls ~0.1 s): 20 events of
  // 5 g, about 2.4 grains of a (10.5 mg) and 0.7 of b (35.3 mg) each.
  REQUIRE(rows.size() > 50);
  // Centres start in y = 0.100 + r .. 0.1032 - r. A grain joins the table in the step at or after its
  // event's time (one dt late at most) and is counted out at the first check after it crosses y = 0
  // (one outlet interval late at most, plus the step it is queued in).
  const double radius[2] = {1e-3, 1.5e-3};
  for (const auto& row : rows) {
    REQUIRE(row.size() == 6);
    const int type = static_cast<int>(row[1]);
    REQUIRE((type == 0 || type == 1));
    const double lo = fall_time(0.1 + radius[type]), hi = fall_time(0.1032 - radius[type]);
    INFO("grain " << row[0] << " species " << type << " residence " << row[5] << " s, closed form " << lo << " .. "
                  << hi << " s");
    CHECK(row[5] == Approx(row[4] - row[3]).margin(1e-12));
    CHECK(row[5] >= lo - 1e-9);
    CHECK(row[5] <= hi + kOutletEvery + 2.0 * kDt);
  }
  // Mass conservation at every series row: what is in the table is what was fed less what left, and
  // the fed mass is the rate times the time fed, less at most one grain's worth owed per species.
  const auto series = csv_rows(dir.path / "run" / "series.csv");
  const auto header = read_lines(dir.path / "run" / "series.csv").front();
  REQUIRE_THAT(header, Contains("grains,holdup_mass,fed_mass,discharged_mass,feed_backlog"));
  const std::size_t c = series.front().size() - 5;
  const double mass[2] = {2500.0 * 4.0 / 3.0 * M_PI * 1e-9, 2500.0 * 4.0 / 3.0 * M_PI * 3.375e-9};
  for (const auto& row : series) {
    const double t = row[0];
    CHECK(row[c + 1] == Approx(row[c + 2] - row[c + 3]).margin(1e-15));
    // The row at t follows the step that ends at t; an event due at t is held by the next step.
    const double events = std::floor((t - 1e-9) / 0.01) + 1.0;
    const double owed = 0.01 * 0.01 * events;
    CHECK(row[c + 2] <= owed + 1e-15);
    CHECK(row[c + 2] >= owed - mass[0] - mass[1] - 1e-15);
  }
  const auto summary = read_file(dir.path / "run" / "summary.json");
  CHECK_THAT(summary, Contains("\"residence_rows\": " + std::to_string(rows.size())));
}

TEST_CASE("flow: a continuous run in two pieces writes the same files as one run", "[flow][checkpoint][cli]") {
  TempDir dir("flow_ckpt");
  const fs::path scene = dir.write("fall.toml", free_fall_scene());
  const fs::path one = dir.path / "one", two = dir.path / "two";
  // 7,000 steps (0.14 s) in the first piece: grains are in the table, queued and leaving then.
  auto a = run_cli(dir, args(scene, one, "--steps 12000 --set output.checkpoint_interval=0.035"));
  REQUIRE(a.code == 0);
  auto b = run_cli(dir, args(scene, two, "--steps 7000 --set output.checkpoint_interval=0.035"));
  REQUIRE(b.code == 0);
  auto c = run_cli(dir, args(scene, two,
                             "--steps 12000 --set output.checkpoint_interval=0.035 --resume " +
                                 quote((two / "checkpoints" / "checkpoint.gfc").string())));
  INFO(c.err);
  REQUIRE(c.code == 0);
  CHECK(read_lines(one / "residence.csv").size() > 20);
  CHECK(read_file(one / "residence.csv") == read_file(two / "residence.csv"));
  CHECK(read_lines(one / "layers.csv").size() > 10);
  CHECK(read_file(one / "layers.csv") == read_file(two / "layers.csv"));
  CHECK(read_file(one / "final_state.csv") == read_file(two / "final_state.csv"));
  CHECK(read_file(one / "series.csv") == read_file(two / "series.csv"));
  CHECK(read_file(one / "checkpoints" / "checkpoint.gfc") == read_file(two / "checkpoints" / "checkpoint.gfc"));
  // The checkpoint of a continuous run does not resume a scene without its feed.
  const std::string s = free_fall_scene();
  const fs::path plain = dir.write("plain.toml", s.substr(0, s.find("[[feed]]")) + "[output]\nseries_interval = 0.01\n" +
                                                     "[[fill]]\nkind = \"random\"\ncount = { a = 5 }\n"
                                                     "region = { shape = \"box\", lo = [0, 0.2, 0], "
                                                     "hi = [0.01, 0.21, 0.01] }\n");
  auto d = run_cli(dir, args(plain, dir.path / "three",
                             "--resume " + quote((two / "checkpoints" / "checkpoint.gfc").string())));
  CHECK(d.code != 0);
  CHECK_THAT(d.err, Contains("[[feed]] or [[outlet]]"));
}

TEST_CASE("flow: feed and outlet tables with a problem are refused naming the key and the fix", "[flow][scene]") {
  const auto error = [](const std::string& text) {
    try {
      gf::DemSimulation::from_text(text);
    } catch (const gf::SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string ok = free_fall_scene();
  CHECK(error(ok).empty());
  auto with = [&](const std::string& from, const std::string& to) {
    std::string s = ok;
    const auto at = s.find(from);
    REQUIRE(at != std::string::npos);
    return s.replace(at, from.size(), to);
  };
  CHECK_THAT(error(with("a = 0.5, b = 0.5", "a = 0.5, b = 0.4")), Contains("sum to 0.9, not 1"));
  CHECK_THAT(error(with("a = 0.5, b = 0.5", "a = 0.5, c = 0.5")), Contains("no species is named 'c'"));
  CHECK_THAT(error(with("interval = 0.01", "interval = 1e-6")), Contains("shorter than the time step"));
  CHECK_THAT(error(with("mass_rate = 0.01", "mass_rate = -1")), Contains("mass_rate"));
  CHECK_THAT(error(with("mass_rate = 0.01", "mass_rate = 5000")), Contains("at most 1,000,000 grains"));
  CHECK_THAT(error(with("interval = 0.01", "interval = 0.01\nstart = 0.5\nstop = 0.2")),
             Contains("stops before it starts"));
  // Without a feed, a scene still needs grains from a fill.
  const auto no_feed = ok.substr(0, ok.find("[[feed]]")) + ok.substr(ok.find("[[outlet]]"));
  CHECK_THAT(error(no_feed), Contains("places no grains"));
}
