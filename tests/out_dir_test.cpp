// The output folder a run claims (app/out_dir.hpp): a folder that holds files is refused with a fix, unless
// the run resumes or --overwrite clears it, and --overwrite clears only a run's folder.
#include <catch2/catch.hpp>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "app/cli.hpp"
#include "app/out_dir.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

gf::CliOptions run_into(const fs::path& out) {
  gf::CliOptions o;
  o.command = "run";
  o.scene = "scene.toml";
  o.out = out;
  return o;
}

std::string refusal(const gf::CliOptions& o) {
  try {
    gf::claim_out_dir(o);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("out dir: a new or empty folder is taken as it is", "[cli]") {
  gf::test::TempDir dir("out_dir_new");
  CHECK(refusal(run_into(dir.path / "new")).empty());
  CHECK(!fs::exists(dir.path / "new"));  // created by the run, not by the claim
  fs::create_directories(dir.path / "empty");
  CHECK(refusal(run_into(dir.path / "empty")).empty());
}

TEST_CASE("out dir: a folder with an earlier run is refused unless resumed or overwritten", "[cli]") {
  gf::test::TempDir dir("out_dir_run");
  const fs::path out = dir.path / "run";
  fs::create_directories(out / "frames");
  dir.write("run/summary.json", "{}");
  dir.write("run/frames/frame_000000.vtp", "old");
  dir.write("run/series.csv", "old");
  gf::CliOptions o = run_into(out);
  const std::string e = refusal(o);
  CHECK_THAT(e, Contains("already holds frames/, series.csv, summary.json") && Contains("Fix: add --overwrite") &&
                    Contains("--resume " + (out / "checkpoints" / "checkpoint.gfc").string()));
  CHECK(fs::exists(out / "series.csv"));  // refused: nothing removed

  o.resume = out / "checkpoints" / "checkpoint.gfc";
  CHECK(refusal(o).empty());
  CHECK(fs::exists(out / "series.csv"));  // resumed: the run's files go on

  o.resume.reset();
  o.overwrite = true;
  CHECK(refusal(o).empty());
  CHECK(fs::is_directory(out));
  CHECK(fs::is_empty(out));  // cleared, the folder kept
}

TEST_CASE("out dir: --overwrite never empties a folder that is not a run's", "[cli]") {
  gf::test::TempDir dir("out_dir_other");
  fs::create_directories(dir.path / "notes");
  dir.write("notes/thesis.tex", "years of work");
  gf::CliOptions o = run_into(dir.path / "notes");
  o.overwrite = true;
  CHECK_THAT(refusal(o), Contains("no summary.json") && Contains("not a grainflow run's folder") && Contains("Fix:"));
  CHECK(fs::exists(dir.path / "notes" / "thesis.tex"));
  // A file where the folder should be.
  dir.write("file", "x");
  CHECK_THAT(refusal(run_into(dir.path / "file")), Contains("is a file") && Contains("Fix:"));
}
