#include "app/cli.hpp"

#include <CLI/CLI.hpp>

#include <charconv>
#include <cmath>

#include "engine/user_text.hpp"

namespace gf {

std::filesystem::path CliOptions::out_dir() const {
  return out ? *out : std::filesystem::path("runs") / scene.stem();
}

std::string usage(std::string_view program) {
  const std::string p(program);
  return "usage:\n"
         "  " + p + " run SCENE [--out DIR] [--overwrite] [--threads N] [--steps N] [--set key=value]...\n"
         "  " + std::string(p.size() + 5, ' ') + "[--resume CHECKPOINT] [--rebalance RATIO] [--quiet]\n"
         "  " + p + " check SCENE [--set key=value]... [--keys]\n"
         "  " + p + " --help | --version\n"
         "check validates a scene (and builds its fills) and prints what a run would do; run writes series.csv,\n"
         "frames, pictures, checkpoints and summary.json to DIR (default runs/<scene name>). An option takes its\n"
         "value as --opt value or --opt=value.\n"
         "  --overwrite  clear DIR first when it holds an earlier run (a run into a folder that holds files is\n"
         "               refused otherwise, unless it resumes)\n"
         "  --threads    1 to " + std::to_string(kMaxThreads) + " (default: all cores)\n"
         "  --steps      main-stage steps instead of the scene's duration\n"
         "  --set        override a scene key, e.g. --set run.dt=2e-5 --set fill.0.count.small=1000\n"
         "  --resume     continue the run from this checkpoint (DIR/checkpoints/checkpoint.gfc; a run on several\n"
         "               ranks: DIR/checkpoints/checkpoint_ranks.gfc)\n"
         "  --rebalance  on several MPI ranks: cut the ranks' boxes again where the costliest rank's grains cost\n"
         "               more than RATIO times the mean (default 1.25; 0: never; one process has one box)\n"
         "  --keys       list every key the scene's systems read (set or left at its default), one 'key: PATH' each\n";
}

std::string version_line(std::string_view program) { return std::string(program) + " " + GRAINFLOW_VERSION + "\n"; }

namespace {

std::string cut(const std::string& v) { return quoted(v, 40); }

std::int64_t to_int(const std::string& flag, const std::string& v, std::int64_t lo, std::int64_t hi) {
  std::int64_t x = 0;
  auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
  if (ec != std::errc() || p != v.data() + v.size() || x < lo || x > hi)
    throw CliError(flag + " needs an integer from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                   cut(v));
  return x;
}

double to_ratio(const std::string& flag, const std::string& v) {
  double x = 0.0;
  auto [p, ec] = std::from_chars(v.data(), v.data() + v.size(), x);
  if (ec != std::errc() || p != v.data() + v.size() || !(x == 0.0 || (x > 1.0 && std::isfinite(x))))
    throw CliError(flag + " needs 0 (never) or a ratio above 1, got " + cut(v));
  return x;
}

// The strings as typed, checked and converted after CLI11 has sorted them out.
struct Typed {
  std::string scene, out, threads, steps, resume, rebalance;
  std::vector<std::string> sets;
  std::vector<const CLI::Option*> given;  // the options of the parsed command
  bool has(const std::string& flag) const {
    for (const CLI::Option* op : given)
      if (op->check_lname(flag.substr(2))) return op->count() > 0;
    return false;
  }
};

CLI::App* add_command(CLI::App& app, const std::string& name, Typed& t, CliOptions& o) {
  CLI::App* c = app.add_subcommand(name);
  c->allow_extras();  // unknown options are named below, with the closest known one
  c->add_option("scene", t.scene)->required();
  c->add_option("--set", t.sets)->allow_extra_args(false);
  c->add_flag("--quiet", o.quiet);
  if (name == "check") {
    c->add_flag("--keys", o.keys);
    return c;
  }
  c->add_flag("--overwrite", o.overwrite);
  for (auto [flag, into] : {std::pair{"--out", &t.out}, {"--threads", &t.threads}, {"--steps", &t.steps},
                            {"--resume", &t.resume}, {"--rebalance", &t.rebalance}})
    c->add_option(flag, *into);
  return c;
}

// What CLI11 left over: an unknown option (with the closest known one) or a second scene.
void refuse_extras(const CLI::App& c, const CLI::App& other, const std::string& command) {
  const std::vector<std::string> extra = c.remaining();
  if (extra.empty()) return;
  const std::string& first = extra.front();
  if (first.empty() || first[0] != '-')
    throw CliError("unexpected argument " + cut(first) + " after the scene (one scene a run; --set key=value sets keys)");
  std::vector<std::string> known;
  for (const CLI::Option* op : c.get_options())
    if (!op->get_lnames().empty()) known.push_back("--" + op->get_lnames().front());
  const std::string name = first.substr(0, first.find('='));
  if (name.size() > 2 && other.get_option_no_throw(name) != nullptr)
    throw CliError(name + " is an option of '" + other.get_name() + "', not of '" + command + "'");
  std::string why = "unknown option " + cut(name) + " for '" + command + "'";
  if (auto near = closest(name, known); !near.empty()) why += " (did you mean '" + near + "'?)";
  throw CliError(why);
}

void convert(const Typed& t, CliOptions& o) {
  o.scene = t.scene;
  if (t.has("--out")) o.out = t.out;
  if (t.has("--threads")) o.threads = static_cast<int>(to_int("--threads", t.threads, 1, kMaxThreads));
  if (t.has("--steps")) o.steps = to_int("--steps", t.steps, 0, static_cast<std::int64_t>(1e15));
  if (t.has("--resume")) o.resume = t.resume;
  if (t.has("--rebalance")) o.rebalance = to_ratio("--rebalance", t.rebalance);
  for (const std::string& kv : t.sets) {
    if (kv.find('=') == std::string::npos) throw CliError("--set needs key=value, got " + cut(kv));
    o.overrides.push_back(kv);
  }
}

}  // namespace

CliOptions parse_cli(int argc, char** argv, std::string_view program) {
  CliOptions o;
  for (int a = 1; a < argc; ++a) {  // anywhere on the line, as every program's --help
    const std::string_view arg = argv[a];
    if (arg == "--help" || arg == "-h") o.command = "help";
    if (arg == "--version" && o.command.empty()) o.command = "version";
  }
  if (!o.command.empty()) return o;
  if (argc > 1) {  // the command first; a word that is none gets the closest one
    const std::string first = argv[1];
    if (!first.empty() && first[0] == '-')
      throw CliError("missing command: 'run' or 'check' comes first, then the scene, then " + cut(first));
    if (first != "run" && first != "check") {
      std::string why = "unknown command " + cut(first);
      if (auto near = closest(first, {"run", "check"}); !near.empty()) why += " (did you mean '" + near + "'?)";
      throw CliError(why);
    }
  }
  CLI::App app("grainflow", std::string(program));
  app.require_subcommand(1);
  Typed t;
  CLI::App* run = add_command(app, "run", t, o);
  CLI::App* check = add_command(app, "check", t, o);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    o.command = "help";
    return o;
  } catch (const CLI::CallForAllHelp&) {
    o.command = "help";
    return o;
  } catch (const CLI::RequiredError&) {
    throw CliError(argc < 2 ? "missing command and scene" : "missing scene: the scene file follows the command");
  } catch (const CLI::ArgumentMismatch& e) {  // "--out: 1 required TEXT missing"
    const std::string what = e.what();
    throw CliError(what.substr(0, what.find(':')) + " needs a value");
  } catch (const CLI::ParseError& e) {
    throw CliError(e.what());
  }
  o.command = run->parsed() ? "run" : "check";
  const CLI::App& c = run->parsed() ? *run : *check;
  refuse_extras(c, run->parsed() ? *check : *run, o.command);
  t.given = c.get_options();
  convert(t, o);
  return o;
}

}  // namespace gf
