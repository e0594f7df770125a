// Every scene shipped under scenes/ passes `grainflow check`: found by walking the folder, so a scene
// added there is checked without touching this file. check reads the scene, applies its keys' ranges
// and the critical-step test, and builds its fills as run does (random fills placed, state files
// read), then exits 0 and says "valid"; nothing is stepped.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Contains;
using gf::test::Exit;
using gf::test::quote;
using gf::test::run_cli;
using gf::test::TempDir;

namespace {

// Every *.toml under scenes/ (any depth), relative to the source folder, in name order.
std::vector<std::string> shipped_scenes() {
  const fs::path root = fs::path(GRAINFLOW_SOURCE_DIR);
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root / "scenes"))
    if (e.is_regular_file() && e.path().extension() == ".toml") out.push_back(e.path().lexically_relative(root).string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("scenes: every shipped scene passes grainflow check", "[scenes][cli]") {
  const std::vector<std::string> scenes = shipped_scenes();
  // The walk finds at least the scenes the README lists: a wrong folder or a filter that drops
  // them would otherwise pass with nothing checked.
  auto has = [&](const std::string& s) { return std::find(scenes.begin(), scenes.end(), s) != scenes.end(); };
  auto count_under = [&](const std::string& prefix) {
    return std::count_if(scenes.begin(), scenes.end(), [&](const std::string& s) { return s.rfind(prefix, 0) == 0; });
  };
  CHECK(has("scenes/drum_quick.toml"));
  CHECK(has("scenes/drum_seed000.toml"));
  CHECK(has("scenes/drum_seed000_settled.toml"));
  CHECK(has("scenes/drum_seed000_settled_hertz.toml"));
  CHECK(has("scenes/drum_seed000_quarter.toml"));
  CHECK(has("scenes/bench/settled_layer.toml"));
  CHECK(count_under("scenes/liquid/") >= 6);
  CHECK(count_under("scenes/tests/") >= 4);

  TempDir dir("scenes_check");
  double total = 0.0, slowest = 0.0;
  std::string slowest_scene;
  for (const std::string& scene : scenes) {
    const auto t0 = std::chrono::steady_clock::now();
    const Exit e = run_cli(dir, "check " + quote((fs::path(GRAINFLOW_SOURCE_DIR) / scene).string()));
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    total += s;
    if (s > slowest) slowest = s, slowest_scene = scene;
    INFO(scene << " (" << s << " s)\nstdout: " << e.out << "\nstderr: " << e.err);
    CHECK(e.exited);
    CHECK(e.code == 0);
    CHECK_THAT(e.out, Contains("valid"));
  }
  WARN("grainflow check on " << scenes.size() << " scenes: " << total << " s in all, slowest " << slowest_scene << " ("
                             << slowest << " s)");
}
