#include "engine/cli.hpp"

#include <charconv>
#include <stdexcept>

namespace gf {

std::string usage() {
  return "usage:\n"
         "  grainflow run SCENE [--out DIR] [--threads N] [--steps N] [--set key=value]... [--resume CHECKPOINT] [--quiet]\n"
         "  grainflow check SCENE [--set key=value]... [--keys]\n"
         "  grainflow --help | --version\n"
         "check validates a scene (and builds its fills) and prints what a run would do; run writes series.csv,\n"
         "frames, pictures, checkpoints and summary.json to DIR (default runs/<scene name>). --threads: 1 to " +
         std::to_string(kMaxThreads) + " (default: all cores); --steps: main-stage steps instead of the scene's\n"
         "duration; --set: override a scene key, e.g. --set run.dt=2e-5 --set fill.0.count.small=1000; --keys: list\n"
         "every key the scene's systems read (set or left at its default), one 'key: PATH' line each.\n";
}

namespace {
std::int64_t to_int(const std::string& flag, const std::string& v, std::int64_t lo, std::int64_t hi) {
  std::int64_t x = 0;
  auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
  if (ec != std::errc() || p != v.data() + v.size() || x < lo || x > hi)
    throw std::invalid_argument(flag + " needs an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                                ", got '" + v.substr(0, 40) + (v.size() > 40 ? "...'" : "'"));
  return x;
}
}  // namespace

CliOptions parse_cli(int argc, char** argv) {
  CliOptions o;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--help" || arg == "-h") {
      o.command = "help";
      return o;
    }
    if (arg == "--version") {
      o.command = "version";
      return o;
    }
  }
  if (argc < 3) throw std::invalid_argument("missing command or scene");
  o.command = argv[1];
  if (o.command != "run" && o.command != "check") throw std::invalid_argument("unknown command '" + o.command + "'");
  o.scene = argv[2];
  for (int a = 3; a < argc; ++a) {
    const std::string flag = argv[a];
    auto value = [&]() -> std::string {
      if (a + 1 >= argc) throw std::invalid_argument(flag + " needs a value");
      return argv[++a];
    };
    if (flag == "--out" && o.command == "run")
      o.out = value();
    else if (flag == "--threads" && o.command == "run")
      o.threads = static_cast<int>(to_int(flag, value(), 1, kMaxThreads));
    else if (flag == "--resume" && o.command == "run")
      o.resume = value();
    else if (flag == "--steps" && o.command == "run")
      o.steps = to_int(flag, value(), 0, static_cast<std::int64_t>(1e15));
    else if (flag == "--set") {
      std::string kv = value();
      if (kv.find('=') == std::string::npos) throw std::invalid_argument("--set needs key=value, got '" + kv + "'");
      o.overrides.push_back(kv);
    } else if (flag == "--quiet")
      o.quiet = true;
    else if (flag == "--keys" && o.command == "check")
      o.keys = true;
    else
      throw std::invalid_argument("unknown option '" + flag + "' for '" + o.command + "'");
  }
  return o;
}

}  // namespace gf
