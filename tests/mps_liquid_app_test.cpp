// `grainflow check` and `grainflow run` on a liquid scene (app/liquid_app.cpp): the model is picked from
// the [liquid] table, check describes it without running, run writes series.csv (with surge_front, flushed per
// row), VTK frames with their .pvd index and a completed summary.json.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "mps_support.hpp"
#include "test_support.hpp"

using namespace gf;
namespace fs = std::filesystem;

namespace {
int run(const std::string& args, const fs::path& out_file) {
  const std::string cmd = std::string("'") + GRAINFLOW_BINARY + "' " + args + " > '" + out_file.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

TEST_CASE("check describes a liquid scene: node counts, n0, lambda, the systems and the stability numbers") {
  test::TempDir dir("mps_check");
  REQUIRE(run("check '" + test::liquid_scene("dam_break_2d.toml") + "'", dir.path / "out.txt") == 0);
  const std::string out = test::read_file(dir.path / "out.txt");
  CHECK_THAT(out, Catch::Contains("MPS liquid") && Catch::Contains("800 fluid") && Catch::Contains("n0 = 4.91") &&
                      Catch::Contains("pressure_solve") && Catch::Contains("CFL 0.164"));
}

TEST_CASE("run writes series.csv with surge_front, frames and a completed summary") {
  test::TempDir dir("mps_run");
  const fs::path out = dir.path / "run";
  REQUIRE(run("run '" + test::liquid_scene("dam_break_2d.toml") + "' --quiet --steps 40 --out '" + out.string() +
                  "' --set output.frame_interval=0.01",
              dir.path / "log.txt") == 0);
  const auto lines = test::read_lines(out / "series.csv");
  REQUIRE(lines.size() == 1 + 5);  // header, t = 0 and every 0.005 s (10 steps) up to step 40
  CHECK_THAT(lines[0], Catch::Contains("surge_front") && Catch::Contains("bottom_pressure"));
  CHECK(fs::exists(out / "frames.pvd"));
  CHECK(fs::exists(out / "frames" / "frame_000002.vtp"));
  const auto s = nlohmann::json::parse(test::read_file(out / "summary.json"));
  CHECK(s["status"] == "completed");
  CHECK(s["steps"] == 40);
  CHECK(s["fluid_nodes"] == 800);
  CHECK(s["final"]["surge_front"].get<double>() > 0.146);  // the front has moved off the column's face
}
