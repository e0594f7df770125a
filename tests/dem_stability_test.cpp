// A time step beyond the stability limit is refused at load, and, when forced with
// allow_unstable_dt, the run itself detects the blow-up: it stops with exit status 3, a message
// naming what broke and the fix, and summary.json "failed", keeping what it wrote. The boundary
// for this drum (seed-000 contact parameters, 1 and 3 mm grains, smallest collision period
// 1.19e-4 s): 3e-5 s still runs, 4e-5 s trips the overlap limit, 8e-5 s goes non-finite.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gf::test::quote;
using gf::test::read_file;
using gf::test::run_cli;
using gf::test::TempDir;

namespace {

// The small drum, settled under gravity first.
const std::string kDrum = gf::test::small_drum_scene(9.81, "", 0.1);

gf::test::Exit run_at(const TempDir& dir, const std::string& dt, const std::string& name) {
  const fs::path scene = dir.write("drum.toml", kDrum);
  return run_cli(dir, "run " + quote(scene.string()) + " --out " + quote((dir.path / name).string()) +
                          " --quiet --threads 2 --set run.duration=0.1 --set run.allow_unstable_dt=true --set run.dt=" +
                          dt);
}

}  // namespace

TEST_CASE("stability: a step above the limit is refused unless forced", "[stability]") {
  TempDir dir("stab_refuse");
  const fs::path scene = dir.write("drum.toml", kDrum);
  const auto e = run_cli(dir, "check " + quote(scene.string()) + " --set run.dt=4e-5");
  CHECK(e.code == 1);
  CHECK_THAT(e.err, Contains("run.dt") && Contains("allow_unstable_dt"));
}

TEST_CASE("stability: the run detects a blow-up and says what to change", "[stability]") {
  TempDir dir("stab_run");
  // Three times the seed's step runs (0.25 of the collision period): the limit is not at dt_safety.
  const auto ok = run_at(dir, "3e-5", "ok");
  INFO(ok.err);
  CHECK(ok.code == 0);
  for (const std::string dt : {"4e-5", "8e-5"}) {
    const auto e = run_at(dir, dt, "dt" + dt);
    INFO(dt << ": " << e.err);
    CHECK(e.exited);
    CHECK(e.code == 3);
    CHECK_THAT(e.err, Contains("Fix: reduce"));
    const auto summary = nlohmann::json::parse(read_file(dir.path / ("dt" + dt) / "summary.json"));
    CHECK(summary.at("status") == "failed");
    CHECK_THAT(summary.at("failure").get<std::string>(), Contains("Fix:"));
  }
}
