// A run whose outputs cannot be written (a full disk, here a file-size limit) stops with a message
// that says so and how to go on; every file it wrote before stays whole; resuming from its last
// checkpoint once there is room gives the files of a run that never failed.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <sys/wait.h>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gf::test::quote;
using gf::test::read_file;
using gf::test::read_lines;
using gf::test::TempDir;

namespace {

// The one-sphere drop of scenes/tests, sampled every 0.1 ms with a frame every ms and a checkpoint
// every 5 ms: series.csv passes 8 KiB after about 150 rows (15 ms), when the 5 ms and 10 ms
// checkpoints (3 KiB each) and 15 frames (1 KiB each) are written and the 15 ms checkpoint may be.
std::string scene_text() {
  return read_file(fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/tests/sphere_on_plane.toml") +
         "\n[output]\nseries_interval = 1.0e-4\nframe_interval = 1.0e-3\ncheckpoint_interval = 5.0e-3\n";
}

struct Result {
  int code = -1;
  std::string err;
};

// `grainflow run` of the scene with --steps 5000 (50 ms), after `limit` in the shell (a ulimit, or "").
Result run(const TempDir& dir, const fs::path& out, const std::string& limit, const std::string& more = "") {
  const fs::path err = dir.path / "stderr.txt";
  const std::string cmd = limit + quote(GRAINFLOW_BINARY) + " run " + quote((dir.path / "scene.toml").string()) +
                          " --out " + quote(out.string()) + " --steps 5000 --threads 1 --quiet " + more + " 2> " +
                          quote(err.string()) + " > /dev/null < /dev/null";
  const int status = std::system(cmd.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_file(err)};
}

}  // namespace

TEST_CASE("a run past a file-size limit stops with the fix, keeps whole files and resumes to the same result",
          "[output]") {
  TempDir dir("write_failure");
  dir.write("scene.toml", scene_text());
  fs::copy_file(fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/tests/sphere_on_plane.csv", dir.path / "sphere_on_plane.csv");
  const fs::path whole = dir.path / "whole", cut = dir.path / "cut";

  const Result ok = run(dir, whole, "");
  REQUIRE(ok.code == 0);
  const auto whole_rows = read_lines(whole / "series.csv");
  REQUIRE(whole_rows.size() == 502);  // header, t = 0 and 500 samples

  // ulimit -f counts 512-byte blocks in sh (dash), 1024-byte ones in bash: 16 is 8 or 16 KiB, and
  // series.csv (about 27 KiB in all) passes either.
  const Result failed = run(dir, cut, "ulimit -f 16; ");
  INFO(failed.err);
  CHECK(failed.code == 3);
  CHECK_THAT(failed.err, Contains("cannot write time series") && Contains("File too large"));
  CHECK_THAT(failed.err, Contains("Every file written before is complete"));
  CHECK_THAT(failed.err, Contains("--resume " + (cut / "checkpoints" / "checkpoint.gfc").string()));
  CHECK_THAT(read_file(cut / "summary.json"), Contains("\"status\": \"failed\""));

  // What was written stays valid: series.csv holds whole rows only, each the row of the run without a
  // limit (the file was cut back to its last complete row), and the frame index names only frames on disk.
  const auto cut_rows = read_lines(cut / "series.csv");
  REQUIRE(cut_rows.size() > 2);
  REQUIRE(cut_rows.size() < whole_rows.size());
  for (std::size_t i = 0; i < cut_rows.size(); ++i) CHECK(cut_rows[i] == whole_rows[i]);
  const std::string pvd = read_file(cut / "frames.pvd");
  std::size_t named = 0;
  for (std::size_t at = pvd.find("file=\""); at != std::string::npos; at = pvd.find("file=\"", at + 1), ++named) {
    const std::size_t end = pvd.find('"', at + 6);
    CHECK(fs::is_regular_file(cut / pvd.substr(at + 6, end - at - 6)));
  }
  CHECK(named > 0);

  // With room again, the run resumes from its last checkpoint and ends with the files of the whole run.
  const Result resumed = run(dir, cut, "", "--resume " + quote((cut / "checkpoints" / "checkpoint.gfc").string()));
  INFO(resumed.err);
  REQUIRE(resumed.code == 0);
  CHECK(read_file(cut / "series.csv") == read_file(whole / "series.csv"));
  CHECK(read_file(cut / "final_state.csv") == read_file(whole / "final_state.csv"));
  CHECK(read_file(cut / "frames.pvd") == read_file(whole / "frames.pvd"));
}
