// An in-process mutation fuzzer for everything a user hands grainflow: scene files, --set
// overrides, state CSVs and checkpoints. Each input is a scene of scenes/ (with its state file)
// changed by a few random mutations (tests/input_fuzz_mutator.hpp) and given to `check` exactly
// as the command line does; an input `check` accepts is then run for a few steps, and a mutated
// checkpoint is resumed.
//
// Invariants, each input:
//  - no crash (a crash ends the test; the input is left in the work folder to reproduce it),
//  - at most `max_seconds` of wall time, and the process's peak memory under `max_rss_mb`,
//  - a refusal is a SceneError or CheckpointError whose message names the file and the line (or
//    the --set argument) and gives a fix; any other exception is a defect,
//  - an input `check` accepts is not refused by `run` (a run may still stop as unstable after it
//    started: counted and listed in the report).
#pragma once

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <typeinfo>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/checkpoint_file.hpp"
#include "app/cli.hpp"
#include "engine/machine_memory.hpp"
#include "engine/scene.hpp"
#include "tests/input_fuzz_mutator.hpp"
#include "tests/test_support.hpp"

namespace gf::fuzz {

enum class Target { Scene, Override, StateCsv, Checkpoint };
inline const char* target_name(Target t) {
  static const char* names[] = {"scene", "override", "state_csv", "checkpoint"};
  return names[static_cast<int>(t)];
}

struct Settings {
  std::uint64_t seed = 1;
  std::size_t inputs = 1000;
  std::vector<std::string> scenes;       // bases, paths under scenes/
  std::vector<std::string> checkpoints;  // scenes whose checkpoints are mutated and resumed
  double max_seconds = 30.0;             // per input
  double max_rss_mb = 2048.0;            // the process's peak
  std::size_t memory_limit = std::size_t(64) << 20;  // what a scene may plan for (gf::memory_limit)
  std::int64_t run_steps = 3;            // steps of `run` for an input `check` accepts
};

struct Outcome {
  enum class Kind { Accepted, Refused, Defect } kind = Kind::Accepted;
  std::string type;  // "SceneError", "CheckpointError", or what was thrown instead
  std::string what;
};

struct Report {
  std::map<std::string, std::size_t> inputs, accepted, refused;  // by target
  std::map<std::string, std::size_t> refusals_by_kind;           // by exception type and problem
  std::size_t runs = 0, runs_unstable = 0;
  std::vector<std::string> defects, unstable;
  double max_seconds = 0, total_seconds = 0, peak_rss_mb = 0;
  std::string slowest;

  // Adds another report's counts (a run in pieces).
  void merge(const nlohmann::json& j) {
    auto add = [](std::map<std::string, std::size_t>& to, const nlohmann::json& from) {
      for (auto it = from.begin(); it != from.end(); ++it) to[it.key()] += it.value().get<std::size_t>();
    };
    add(inputs, j["inputs_by_target"]), add(accepted, j["accepted_by_target"]), add(refused, j["refused_by_target"]);
    add(refusals_by_kind, j["refusals_by_kind"]);
    runs += j["runs_after_check"].get<std::size_t>(), runs_unstable += j["runs_unstable"].get<std::size_t>();
    for (const auto& d : j["defect_examples"]) defects.push_back(d.get<std::string>());
    for (const auto& u : j["unstable_examples"]) if (unstable.size() < 20) unstable.push_back(u.get<std::string>());
    if (j["max_seconds_per_input"].get<double>() > max_seconds)
      max_seconds = j["max_seconds_per_input"].get<double>(), slowest = j["slowest_input"].get<std::string>();
    total_seconds += j["total_seconds"].get<double>();
    peak_rss_mb = std::max(peak_rss_mb, j["peak_rss_mb"].get<double>());
  }

  nlohmann::json json(const Settings& s) const {
    return {{"seed", s.seed}, {"inputs", s.inputs}, {"scenes", s.scenes}, {"checkpoint_scenes", s.checkpoints},
            {"inputs_by_target", inputs}, {"accepted_by_target", accepted}, {"refused_by_target", refused},
            {"refusals_by_kind", refusals_by_kind}, {"runs_after_check", runs}, {"runs_unstable", runs_unstable},
            {"unstable_examples", unstable}, {"defects", defects.size()}, {"defect_examples", defects},
            {"max_seconds_per_input", max_seconds}, {"slowest_input", slowest}, {"total_seconds", total_seconds},
            {"peak_rss_mb", peak_rss_mb}, {"limits", {{"max_seconds", s.max_seconds}, {"max_rss_mb", s.max_rss_mb},
                                                      {"memory_limit_mb", s.memory_limit >> 20}}}};
  }
};

// stdout and stderr to /dev/null while it lives: `check` and `run` print as they do for a user.
class Silence {
 public:
  Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    out_ = ::dup(1), err_ = ::dup(2);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, 1), ::dup2(null, 2), ::close(null);
  }
  ~Silence() {
    std::fflush(stdout);
    std::fflush(stderr);
    ::dup2(out_, 1), ::dup2(err_, 2), ::close(out_), ::close(err_);
  }
  Silence(const Silence&) = delete;
  Silence& operator=(const Silence&) = delete;

 private:
  int out_, err_;
};

// JSON as text; invalid UTF-8 (a mutated value echoed in a message) is replaced, not thrown on.
inline std::string dump(const nlohmann::json& j) {
  return j.dump(1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// The problem of a message "<where>: key '<k>': <problem>. Fix: ...", with quoted text shown as '...'
// and numbers as #, for counting refusals by kind.
inline std::string problem_of(std::string m) {
  if (const auto k = m.find("key '"); k != std::string::npos) m = m.substr(m.find("': ", k) + 3);
  else if (const auto c = m.rfind(": ", m.find(". Fix:")); c != std::string::npos) m = m.substr(c + 2);
  m = m.substr(0, m.find(". Fix:"));
  std::string out;
  bool in_quote = false;
  for (const char c : m) {
    if (c == '\'') {
      in_quote = !in_quote;
      out += in_quote ? "'...'" : "";
    } else if (!in_quote && !(c >= '0' && c <= '9' && !out.empty() && out.back() == '#')) {
      out += c >= '0' && c <= '9' ? '#' : c;
    }
  }
  return out.substr(0, 64);
}

class Fuzzer {
 public:
  explicit Fuzzer(Settings s) : s_(std::move(s)), dir_("input_fuzz"), m_(s_.seed) {
    for (const std::string& b : s_.scenes) bases_.push_back(load_base(b));
    for (const std::string& b : s_.checkpoints) ckpt_bases_.push_back(load_base(b));
    ::mkfifo((dir_.path / "fifo").c_str(), 0600);  // a path that would block a reader
    fs::create_directories(dir_.path / "data");
  }

  const fs::path& work() const { return dir_.path; }

  Report run() {
    memory_limit().store(s_.memory_limit);
    make_checkpoints();
    for (std::size_t i = 0; i < s_.inputs; ++i) one(i);
    memory_limit().store(0);
    return r_;
  }

 private:
  // Files of base `b` (with `text` and `csv`) in the work folder; returns the scene's path. The scene sits two
  // folders down, so that a state file the scene names up a folder ("../data/x.csv") lands inside the work
  // folder too, never in one that another fuzzing process shares.
  fs::path place(const Base& b, const std::string& text, const std::string& csv) const {
    const fs::path home = dir_.path / "in" / "scenes";
    fs::create_directories(home);
    if (!b.csv_name.empty() && b.csv_name.find('\0') == std::string::npos) {
      const fs::path p = (home / b.csv_name).lexically_normal();
      const fs::path inside = fs::relative(p, dir_.path);
      if (inside.empty() || *inside.begin() == "..")
        throw std::logic_error("the state file " + b.csv_name + " lies outside the fuzzer's work folder");
      fs::create_directories(p.parent_path());
      dir_.write(inside.string(), csv);
    }
    return dir_.write(fs::relative(home / b.file, dir_.path).string(), text);
  }

  // The run's overrides: none, or no settling for a scene that settles first, so that a few steps
  // of `run` are a few steps.
  static std::vector<std::string> quick(const Base& b, std::vector<std::string> o) {
    if (b.text.find("\n[settle]") != std::string::npos) o.push_back("settle.time=0");
    return o;
  }

  CliOptions options(const fs::path& scene, std::vector<std::string> overrides) const {
    CliOptions o;
    o.scene = scene;
    o.overrides = std::move(overrides);
    o.out = dir_.path / "out";
    o.quiet = true;
    return o;
  }

  void make_checkpoints() {
    for (const Base& b : ckpt_bases_) {
      CliOptions o = options(place(b, b.text, b.csv_text), quick(b, {}));
      o.command = "run";
      o.steps = 5;
      o.out = dir_.path / ("ckpt_" + b.file);
      {
        Silence quiet;
        run_command(o);
      }
      ckpts_.push_back(test::read_file(*o.out / "checkpoints" / "checkpoint.gfc"));
    }
  }

  template <class F>
  Outcome guarded(F&& f, const fs::path& scene, const fs::path& ckpt) {
    try {
      Silence quiet;
      f();
      return {};
    } catch (const SceneError& e) {
      return refusal("SceneError", e.what(), scene);
    } catch (const CheckpointError& e) {
      return refusal("CheckpointError", e.what(), ckpt);
    } catch (const std::exception& e) {
      return {Outcome::Kind::Defect, typeid(e).name(), e.what()};
    } catch (...) {
      return {Outcome::Kind::Defect, "unknown", ""};
    }
  }

  // A refusal must say where (file and line, or the --set argument, or the checkpoint) and the fix.
  static Outcome refusal(const std::string& type, const std::string& what, const fs::path& file) {
    const std::string f = file.string();
    bool located = what.rfind("command line (--set ", 0) == 0;
    if (what.rfind(f + ":", 0) == 0) {
      const std::size_t p = f.size() + 1;
      std::size_t q = p;
      while (q < what.size() && std::isdigit(static_cast<unsigned char>(what[q]))) ++q;
      located = located || (q > p && q < what.size() && what[q] == ':') || type == "CheckpointError";
    }
    const bool fix = what.find("Fix: ") != std::string::npos;
    if (located && fix) return {Outcome::Kind::Refused, type, what};
    return {Outcome::Kind::Defect, type + (located ? " without a fix" : " without file and line"), what};
  }

  void one(std::size_t index) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto target = static_cast<Target>(m_.below(ckpts_.empty() ? 3 : 4));
    const std::string tname = target_name(target);
    ++r_.inputs[tname];
    Outcome out = target == Target::Checkpoint ? resume_one() : check_one(target);
    const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    record(index, tname, out, sec);
  }

  Outcome check_one(Target target) {
    const Base& b = bases_[m_.below(bases_.size())];
    std::string text = b.text, csv = b.csv_text;
    std::vector<std::string> overrides;
    if (target == Target::Override) overrides = m_.overrides(text);
    if (target == Target::StateCsv && b.csv_name.empty()) target = Target::Scene;
    for (std::size_t k = 0, n = 1 + m_.below(3); k < n; ++k) {
      if (target == Target::Scene) text = m_.scene_text(text);
      if (target == Target::StateCsv) csv = m_.csv_text(csv);
    }
    const fs::path scene = place(b, text, csv);
    last_ = b.name + " " + std::string(target_name(target)) + (overrides.empty() ? "" : " --set");
    for (const std::string& o : overrides) last_ += " '" + gf::clipped(o, 80) + "'";
    dir_.write("last_input.txt", last_ + "\n");  // left behind by a crash, to reproduce it
    CliOptions o = options(scene, overrides);
    Outcome c = guarded([&] { check_command(o); }, scene, {});
    if (c.kind != Outcome::Kind::Accepted) return c;
    // Accepted: then run must not refuse it (checked again without settling, so the run is short).
    o.overrides = quick(b, overrides);
    if (guarded([&] { check_command(o); }, scene, {}).kind != Outcome::Kind::Accepted) return c;
    return run_one(o, scene);
  }

  Outcome run_one(CliOptions o, const fs::path& scene) {
    o.command = "run";
    o.steps = s_.run_steps;
    fs::remove_all(*o.out);
    int rc = 0;
    Outcome r = guarded([&] { rc = run_command(o); }, scene, o.resume ? *o.resume : fs::path());
    ++r_.runs;
    if (r.kind == Outcome::Kind::Refused && !o.resume)
      return {Outcome::Kind::Defect, "run refused what check accepted: " + r.type, r.what};
    if (r.kind == Outcome::Kind::Accepted && rc == 3) {
      ++r_.runs_unstable;
      const std::string why = test::read_file(*o.out / "summary.json");
      const auto at = why.find("\"failure\": ");
      if (r_.unstable.size() < 20)
        r_.unstable.push_back(last_ + ": " + (at == std::string::npos ? "" : why.substr(at + 11, 200)));
    }
    return r;
  }

  Outcome resume_one() {
    const std::size_t k = m_.below(ckpts_.size());
    const Base& b = ckpt_bases_[k];
    const fs::path scene = place(b, b.text, b.csv_text);
    const fs::path ckpt = dir_.write("resume.gfc", m_.checkpoint(ckpts_[k]));
    last_ = b.name + " checkpoint";
    dir_.write("last_input.txt", last_ + "\n");
    CliOptions o = options(scene, quick(b, {}));
    o.resume = ckpt;
    o.steps = 5 + s_.run_steps;
    return run_one(o, scene);
  }

  void record(std::size_t index, const std::string& tname, const Outcome& out, double sec) {
    const std::string id = "input " + std::to_string(index) + " (" + last_ + ")";
    if (out.kind == Outcome::Kind::Accepted) ++r_.accepted[tname];
    if (out.kind == Outcome::Kind::Refused) {
      ++r_.refused[tname];
      ++r_.refusals_by_kind[out.type + ": " + problem_of(out.what)];
    }
    if (out.kind == Outcome::Kind::Defect) r_.defects.push_back(id + ": " + out.type + ": " + gf::clipped(out.what, 300));
    r_.total_seconds += sec;
    if (sec > r_.max_seconds) r_.max_seconds = sec, r_.slowest = id;
    if (sec > s_.max_seconds) r_.defects.push_back(id + ": took " + std::to_string(sec) + " s");
    rusage u{};
    ::getrusage(RUSAGE_SELF, &u);
    const double rss = static_cast<double>(u.ru_maxrss) / 1024.0;
    if (rss > s_.max_rss_mb && r_.peak_rss_mb <= s_.max_rss_mb)
      r_.defects.push_back(id + ": the process's memory passed " + std::to_string(rss) + " MB");
    r_.peak_rss_mb = rss;
  }

  Settings s_;
  test::TempDir dir_;
  Mutator m_;
  std::vector<Base> bases_, ckpt_bases_;
  std::vector<std::string> ckpts_;
  std::string last_;
  Report r_;
};

}  // namespace gf::fuzz
