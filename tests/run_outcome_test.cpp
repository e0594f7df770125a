// How a run's end is recorded (app/run_outcome.hpp): what guarded() makes of a failed write and of any
// other error, that a failed run skips its later writes, and the JSON of a sampled row.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "app/run_outcome.hpp"

using Catch::Matchers::Contains;

TEST_CASE("run outcome: a failed write says how to go on, from the checkpoint when there is one", "[run_outcome]") {
  gf::CliOptions opt;
  opt.scene = "scenes/drum.toml";
  for (const bool have : {true, false}) {
    gf::RunOutcome r;
    gf::guarded(r, opt, "runs/drum", [&] { return have; }, [] { throw gf::WriteError("cannot write 'series.csv'"); });
    INFO("have a checkpoint: " << have);
    CHECK(r.failed());
    CHECK(r.rc == 3);
    CHECK_THAT(r.failure, Contains("cannot write 'series.csv'") && Contains("Fix: free space"));
    if (have) CHECK_THAT(r.failure, Contains("--resume runs/drum/checkpoints/checkpoint.gfc"));
    else CHECK_THAT(r.failure, Contains("run again"));
  }
}

TEST_CASE("run outcome: another error keeps its message; a failed run skips its later writes", "[run_outcome]") {
  gf::CliOptions opt;
  gf::RunOutcome r;
  gf::guarded(r, opt, "out", [] { return false; }, [] { throw std::runtime_error("the run blew up"); });
  CHECK(r.failure == "the run blew up");
  bool ran = false;
  gf::guarded(r, opt, "out", [] { return false; }, [&] { ran = true; });
  CHECK_FALSE(ran);
  r.fail_also("cannot write 'summary.json'");
  CHECK(r.failure == "the run blew up; then cannot write 'summary.json'");
  gf::RunOutcome fresh;
  gf::guarded(fresh, opt, "out", [] { return false; }, [&] { fresh.status = "interrupted"; });
  CHECK(fresh.status == "interrupted");
  CHECK(fresh.rc == 0);
}

TEST_CASE("run outcome: a sampled row as JSON, null where not finite", "[run_outcome]") {
  const nlohmann::json j = gf::row_json({"time", "lacey_index", "angle"},
                                        {0.5, std::numeric_limits<double>::quiet_NaN(), INFINITY});
  CHECK(j["time"].get<double>() == 0.5);
  CHECK(j["lacey_index"].is_null());
  CHECK(j["angle"].is_null());
}
