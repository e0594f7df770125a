// A time step beyond the stability limit is refused at load, and, when forced with
// allow_unstable_dt, the run itself detects the blow-up: it stops with exit status 3, a message
// naming what broke and the fix, and summary.json "failed", keeping what it wrote. The boundary
// for this drum (seed-000 contact parameters, 1 and 3 mm grains, smallest collision period
// 1.19e-4 s), through the command line with its 0.1 s of settling: 3e-5 s still runs; 8e-5 s trips
// the pair-overlap check (two grains) a few steps into settling; a wall far softer than the grains
// (kn = 1 N/m) trips the wall-overlap check at 3e-5 s while it settles. Between 3.7e-5 and 6e-5 s
// which check trips first depends on the round-off of the summation order, so that range is not used. Stepped directly, without the settling
// stage, 4e-5 s trips while the drum turns. The checks run in every step, inside the kernels, and
// name the step and the grains; a non-finite value is put in by hand (a step that large trips the
// overlap limit first).
#include <catch2/catch.hpp>

#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "systems/analysis/metrics.hpp"
#include "systems/setup/dem_simulation.hpp"
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

gf::test::Exit run_at(const TempDir& dir, const std::string& dt, const std::string& name,
                      const std::string& scene_text = kDrum) {
  const fs::path scene = dir.write(name + ".toml", scene_text);
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
  // Which detector fires, by the words of its message (stability_report.cpp): a wall overlap is
  // "overlaps wall '<name>' by ... of its diameter", a pair overlap "grain id ... and grain id ...
  // overlap by ... of the smaller diameter", a non-finite value "became non-finite". Both runs are
  // deterministic (the same step with 1 or 2 threads), so the detector and the stage are fixed.
  struct Case {
    std::string dt, scene, name;
    std::vector<std::string> fired;      // the detector's words
    std::vector<std::string> not_fired;  // the other detectors' words
  };
  // The wall case is a wall a thousand times softer than the grains (kn = 1 N/m) at a stable step:
  // a 6 mm grain resting on it sinks by half its diameter, so the wall check fires whatever the
  // round-off, and no pair comes near the limit. (Past the stable step, which check fires first
  // depends on the round-off of the summation order, which differs between builds.)
  const Case cases[] = {
      {"3e-5", kDrum + "\n[contact.wall]\nkn = 1.0\n", "soft_wall",
       {"overlaps wall 'drum' by ", " of its diameter in step ", " of the settle stage", "past run.max_overlap = 0.1"},
       {" of the smaller diameter", "non-finite"}},
      {"8e-5", kDrum, "dt8e-5",
       {") and grain id ", " of the smaller diameter in step ", " of the settle stage", "past run.max_overlap = 0.1"},
       {"overlaps wall", "non-finite"}},
  };
  for (const Case& c : cases) {
    const auto e = run_at(dir, c.dt, c.name, c.scene);
    INFO(c.name << ": " << e.err);
    CHECK(e.exited);
    CHECK(e.code == 3);
    CHECK_THAT(e.err, Contains("failed while settling"));
    CHECK_THAT(e.err, Contains("Fix: reduce"));
    const auto summary = nlohmann::json::parse(read_file(dir.path / c.name / "summary.json"));
    CHECK(summary.at("status") == "failed");
    const std::string failure = summary.at("failure").get<std::string>();
    CHECK_THAT(failure, Contains("Fix:"));
    for (const std::string& words : c.fired) {
      CHECK_THAT(e.err, Contains(words));
      CHECK_THAT(failure, Contains(words));
    }
    for (const std::string& words : c.not_fired) CHECK_THAT(e.err, !Contains(words));
  }
}

TEST_CASE("stability: an overlap past the limit stops the step that made it, with no output configured",
          "[stability]") {
  // The small drum at 4e-5 s (past the stable step, forced), stepped without any observer (no
  // series, no frames): the check runs inside the contact kernels, so it cannot depend on an output. After every step that
  // passes, an independent all-pairs measure (metrics.hpp) must be within the limit; the step that
  // throws must be the first whose contacts are past it.
  gf::DemSimulation sim = gf::DemSimulation::from_text(
      kDrum, {"run.dt=4e-5", "run.allow_unstable_dt=true"});
  const double limit = sim.scene().max_overlap;
  std::string message;
  std::int64_t steps = 0;
  for (; steps < 20000 && message.empty(); ++steps) {
    try {
      sim.advance(1);
    } catch (const gf::StabilityError& e) {
      message = e.what();
      break;
    }
    gf::World& w = sim.world();
    const auto cs = gf::contact_stats(sim.grains(), w.resources.get<gf::NeighborList>(), w.resources.get<gf::Walls>());
    REQUIRE(cs.max_overlap_ratio <= limit);
  }
  INFO(message);
  REQUIRE_FALSE(message.empty());
  gf::World& w = sim.world();
  const auto cs = gf::contact_stats(sim.grains(), w.resources.get<gf::NeighborList>(), w.resources.get<gf::Walls>());
  CHECK(cs.max_overlap_ratio > limit);  // the state the kernel saw is past the limit
  CHECK_THAT(message, Contains("in step " + std::to_string(steps + 1) + " of the run stage") &&
                          Contains("grain id ") && Contains("run.max_overlap = 0.1") && Contains("Fix: reduce run.dt"));
  // Which check fires first here, a grain into the turning drum's cylinder or one of its ends, or two
  // grains, depends on the round-off of the summation order and so on the machine's SIMD width (the
  // steps near the limit are chaotic); each names its contact. The detectors' own words are pinned by
  // the command-line test above.
  CHECK_THAT(message, (Contains("overlaps wall 'drum") && Contains(" of its diameter")) ||
                          (Contains(") and grain id ") && Contains(" of the smaller diameter")));
}

TEST_CASE("stability: a non-finite value stops the step that made it and names the grain", "[stability]") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(kDrum);
  sim.advance(10);
  gf::Grains& g = sim.grains();
  std::size_t row = 0;
  while (g.pid.id[row] != 42) ++row;
  g.vel.y[row] = std::numeric_limits<double>::infinity();
  try {
    sim.advance(5);
    FAIL("no error");
  } catch (const gf::StabilityError& e) {
    const std::string m = e.what();
    INFO(m);
    CHECK_THAT(m, Contains("grain id 42 ") && Contains("became non-finite in step 11 of the run stage") &&
                      Contains("Fix: reduce run.dt"));
  }
}
