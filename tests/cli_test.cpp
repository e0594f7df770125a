// The command line both programs parse (app/cli.hpp): forms, checks and the messages a mistake gets.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "app/cli.hpp"

using Catch::Matchers::Contains;

namespace {

gf::CliOptions parse(std::vector<std::string> words, const char* program = "grainflow") {
  words.insert(words.begin(), program);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  return gf::parse_cli(static_cast<int>(argv.size()), argv.data(), program);
}

std::string refusal(std::vector<std::string> words) {
  try {
    parse(std::move(words));
  } catch (const gf::CliError& e) {
    return e.what();
  }
  return "(accepted)";
}

}  // namespace

TEST_CASE("cli: --opt value and --opt=value give the same options", "[cli]") {
  const gf::CliOptions a = parse({"run", "s.toml", "--out", "o", "--threads", "2", "--steps", "10", "--set", "run.dt=1e-5",
                                  "--set", "a.b=2", "--resume", "c.gfc", "--rebalance", "1.5", "--quiet"});
  const gf::CliOptions b = parse({"run", "--out=o", "s.toml", "--threads=2", "--steps=10", "--set=run.dt=1e-5",
                                  "--set=a.b=2", "--resume=c.gfc", "--rebalance=1.5", "--quiet"});
  for (const gf::CliOptions* o : {&a, &b}) {
    CHECK(o->command == "run");
    CHECK(o->scene == "s.toml");
    CHECK(o->out_dir() == "o");
    CHECK(o->threads == 2);
    CHECK(o->steps == 10);
    CHECK(o->overrides == std::vector<std::string>{"run.dt=1e-5", "a.b=2"});
    CHECK(o->resume == "c.gfc");
    CHECK(o->rebalance == 1.5);
    CHECK(o->quiet);
  }
}

TEST_CASE("cli: defaults", "[cli]") {
  const gf::CliOptions o = parse({"run", "scenes/drum.toml"});
  CHECK(o.out_dir() == "runs/drum");
  CHECK(o.threads == 0);
  CHECK_FALSE(o.steps);
  CHECK_FALSE(o.resume);
  CHECK(o.rebalance == 1.25);
  CHECK(parse({"check", "s.toml", "--keys"}).keys);
}

TEST_CASE("cli: help and version anywhere, for both programs", "[cli]") {
  for (const auto& words : std::vector<std::vector<std::string>>{{"--help"}, {"-h"}, {"run", "--help"}, {"check", "x", "-h"}})
    CHECK(parse(words).command == "help");
  CHECK(parse({"--version"}).command == "version");
  CHECK(parse({"run", "s.toml", "--version"}, "grainflow_mpi").command == "version");
  CHECK_THAT(gf::version_line("grainflow_mpi"), Contains("grainflow_mpi 0."));
  CHECK_THAT(gf::usage("grainflow_mpi"), Contains("grainflow_mpi run SCENE"));
}

TEST_CASE("cli: each mistake is named with its fix", "[cli]") {
  CHECK(refusal({}) == "missing command and scene");
  CHECK_THAT(refusal({"run"}), Contains("missing scene"));
  CHECK_THAT(refusal({"rnu", "s.toml"}), Contains("unknown command 'rnu' (did you mean 'run'?)"));
  CHECK_THAT(refusal({"--threads", "2"}), Contains("'run' or 'check' comes first"));
  CHECK_THAT(refusal({"run", "s.toml", "--ouT", "x"}), Contains("unknown option '--ouT' for 'run' (did you mean '--out'?)"));
  CHECK_THAT(refusal({"run", "s.toml", "--thread=3"}), Contains("(did you mean '--threads'?)"));
  CHECK(refusal({"run", "s.toml", "--bogus"}) == "unknown option '--bogus' for 'run'");
  CHECK_THAT(refusal({"check", "s.toml", "--out", "x"}), Contains("--out is an option of 'run', not of 'check'"));
  CHECK_THAT(refusal({"run", "s.toml", "--keys"}), Contains("--keys is an option of 'check'"));
  CHECK(refusal({"run", "s.toml", "--steps"}) == "--steps needs a value");
  CHECK_THAT(refusal({"run", "s.toml", "--set", "a=1", "b=2"}), Contains("unexpected argument 'b=2'"));
  CHECK(refusal({"run", "s.toml", "--set", "a"}) == "--set needs key=value, got 'a'");
}

TEST_CASE("cli: numbers are checked against their ranges", "[cli]") {
  CHECK(refusal({"run", "s.toml", "--threads", "zero"}) == "--threads needs an integer from 1 to 1024, got 'zero'");
  CHECK(refusal({"run", "s.toml", "--threads", "100000"}) == "--threads needs an integer from 1 to 1024, got '100000'");
  CHECK(refusal({"run", "s.toml", "--threads", "0"}) == "--threads needs an integer from 1 to 1024, got '0'");
  CHECK_THAT(refusal({"run", "s.toml", "--steps", "abc"}), Contains("--steps needs an integer from 0 to"));
  CHECK_THAT(refusal({"run", "s.toml", "--steps", "-1"}), Contains("--steps needs an integer"));
  CHECK(refusal({"run", "s.toml", "--rebalance", "0.5"}) == "--rebalance needs 0 (never) or a ratio above 1, got '0.5'");
  CHECK(refusal({"run", "s.toml", "--rebalance", "inf"}) == "--rebalance needs 0 (never) or a ratio above 1, got 'inf'");
  CHECK(parse({"run", "s.toml", "--rebalance", "0"}).rebalance == 0.0);
  // A long value is cut in the message: a pasted file must not become the line.
  CHECK(refusal({"run", "s.toml", "--threads", std::string(5000, '7')}).size() < 120);
}
