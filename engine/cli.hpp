// Command-line interface: `grainflow run SCENE ...` and `grainflow check SCENE`.
// The engine parses the command line; the commands themselves are provided by the model layer
// (systems/setup), which knows which systems a scene needs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace gf {

// More threads than this is a typo (the default is every core).
inline constexpr int kMaxThreads = 1024;

struct CliOptions {
  std::string command;  // "run", "check", or "help" / "version" (print and exit 0)
  std::filesystem::path scene;
  std::optional<std::filesystem::path> out;  // default: runs/<scene name>
  int threads = 0;                           // 0: all cores
  std::optional<std::int64_t> steps;         // main-stage steps instead of the scene's duration
  std::vector<std::string> overrides;        // key=value
  bool quiet = false;                        // no progress lines
  bool keys = false;                         // check: also list every key the scene's systems read
  std::optional<std::filesystem::path> resume;  // continue from this checkpoint
};

// Parses argv; throws std::invalid_argument with a usage hint on bad arguments.
CliOptions parse_cli(int argc, char** argv);
std::string usage();

int run_command(const CliOptions& opt);    // defined by the model layer
int check_command(const CliOptions& opt);  // defined by the model layer

}  // namespace gf
