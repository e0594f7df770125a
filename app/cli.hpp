// The command line of both programs, parsed once (CLI11):
//   grainflow run SCENE [--out DIR] [--overwrite] [--threads N] [--steps N] [--set key=value]...
//                       [--resume CHECKPOINT] [--rebalance RATIO] [--quiet]
//   grainflow check SCENE [--set key=value]... [--keys]
//   grainflow --help | --version
// grainflow_mpi takes the same words (its `check` runs as grainflow's does). Options take their value as
// `--opt value` or `--opt=value`; a mistyped option is answered with the closest one ("did you mean").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gf {

// More threads than this is a typo (the default is every core).
inline constexpr int kMaxThreads = 1024;

struct CliOptions {
  std::string command;  // "run", "check", or "help" / "version" (print and exit 0)
  std::filesystem::path scene;
  std::optional<std::filesystem::path> out;  // default: runs/<scene name>
  bool overwrite = false;                    // clear an earlier run's folder (app/out_dir.hpp)
  int threads = 0;                           // 0: all cores
  std::optional<std::int64_t> steps;         // main-stage steps instead of the scene's duration
  std::vector<std::string> overrides;        // key=value
  bool quiet = false;                        // no progress lines
  bool keys = false;                         // check: also list every key the scene's systems read
  std::optional<std::filesystem::path> resume;  // continue from this checkpoint
  // Runs on several ranks: the boxes are cut again past this ratio of the costliest rank's grains to
  // the mean (0: never). A run on one process has one box and ignores it.
  double rebalance = 1.25;

  // The output folder: --out, or runs/<scene name>.
  std::filesystem::path out_dir() const;
};

// A command line that cannot be read: what() names the option and the fix, usage() follows it.
struct CliError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Parses argv for `program` ("grainflow" or "grainflow_mpi"); throws CliError on bad arguments.
// --help and --version return with command "help" / "version" (print usage() / version_line()).
CliOptions parse_cli(int argc, char** argv, std::string_view program = "grainflow");
std::string usage(std::string_view program = "grainflow");
std::string version_line(std::string_view program = "grainflow");

int run_command(const CliOptions& opt);    // app/commands.cpp
int check_command(const CliOptions& opt);  // app/commands.cpp

}  // namespace gf
