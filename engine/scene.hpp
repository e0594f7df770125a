// Scene files: a checked reader on top of toml++.
//
// Every system reads its own section through SceneNode. The reader exists so that every bad input (a typo, a
// missing key, a wrong type, a value out of its physical range, a broken --set) stops the program *before anything
// runs* with one message naming the file, the line, the key and what to change:
//
//     drum.toml:12: key 'run.dt': value -1e-05 is out of range, it must be > 0. Fix: set `dt` to a value > 0
//
// Keys that no system read are errors too (SceneDoc::check_all_used, called once all systems are built), because a
// misspelt optional key otherwise silently falls back to its default — the most expensive kind of scene bug.
//
// toml++ is kept out of this header on purpose: every system includes it, and toml.h is large.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "engine/user_text.hpp"

namespace gf {

namespace detail {
struct SceneState;
struct SceneAccess;
}  // namespace detail

// Thrown for any bad scene input. what() is the full message:
//   "<file>:<line>: key '<dotted.path>': <problem>. Fix: <fix>"
// For a value that came from the command line the location is "command line (--set <path>=<value>)".
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string msg);
};

// A number for a message: four significant digits ("0.0001", "2.5e+04").
std::string short_number(double v);
// A number as typed, in full ("2.5", "1e-5"): the shortest text that reads back as the same double.
std::string number_text(double v);



// Allowed interval for a number. Infinite bounds are open by default, so Range::any() also rejects inf and nan:
// no physical input of a scene is meant to be infinite.
struct Range {
  double lo, hi;
  bool lo_open, hi_open;

  static Range any();                                // (-inf, inf)
  static Range positive();                           // (0, inf)
  static Range non_negative();                       // [0, inf)
  static Range closed(double lo, double hi);         // [lo, hi]
  static Range open_closed(double lo, double hi);    // (lo, hi]

  bool contains(double v) const;
  std::string describe() const;  // "> 0", ">= 0", "in [0, 1]", "in (0, 1]", "a finite number" ...
};

class SceneDoc;

// A view of one TOML table inside a SceneDoc. Cheap to copy; keeps the document alive.
// Reading a key (get_*, table, maybe_table, tables) marks it used; `has` and `keys` mark nothing.
// Not thread-safe: scenes are read by one thread while the schedule is built.
class SceneNode {
 public:
  bool has(std::string_view key) const;

  double get_double(std::string_view key, Range r = Range::any()) const;   // required; integers are accepted
  double get_double(std::string_view key, double fallback, Range r) const;  // optional
  std::int64_t get_int(std::string_view key, std::int64_t lo, std::int64_t hi) const;  // inclusive bounds
  std::int64_t get_int(std::string_view key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) const;
  bool get_bool(std::string_view key) const;
  bool get_bool(std::string_view key, bool fallback) const;
  std::string get_string(std::string_view key) const;
  std::string get_string(std::string_view key, std::string fallback) const;
  std::string get_choice(std::string_view key, std::vector<std::string> choices) const;  // must be one of
  std::string get_choice(std::string_view key, std::vector<std::string> choices, std::string fallback) const;
  std::array<double, 3> get_vec3(std::string_view key) const;  // array of exactly 3 finite numbers
  std::array<double, 3> get_vec3(std::string_view key, std::array<double, 3> fallback) const;
  std::vector<double> get_doubles(std::string_view key) const;  // array of finite numbers, any length
  // A non-empty array of [x, y, z] arrays, e.g. positions = [[0, 1, 0], [0, 2, 0]].
  std::vector<std::array<double, 3>> get_vec3_list(std::string_view key) const;

  SceneNode table(std::string_view key) const;  // required sub-table ([a.b] or a = { ... })
  std::optional<SceneNode> maybe_table(std::string_view key) const;
  bool holds_table(std::string_view key) const;  // the key is present and its value is a table
  std::vector<SceneNode> tables(std::string_view key) const;  // array of tables ([[key]]); empty if absent

  // Keys of this table in file order (keys set only on the command line come last). For free-form maps such as
  // `counts = { small = 10, large = 3 }`; does NOT mark them used, so read each one with a get_* call.
  std::vector<std::string> keys() const;

  int line(std::string_view key) const;  // line of the key's value; 0 if absent or set on the command line
  int line() const;                      // line where this table starts; 0 if it came from the command line
  std::string path(std::string_view key) const;  // dotted path for messages: "wall[2].radius" (0-based)
  const std::string& path() const { return path_; }  // this table's own path; "" for the root

  // Throws SceneError at the key's location, or at this table's location if the key is absent.
  [[noreturn]] void fail(std::string_view key, std::string_view problem, std::string_view fix) const;

  const SceneDoc& doc() const;

 private:
  friend class SceneDoc;
  friend struct detail::SceneAccess;
  SceneNode(std::shared_ptr<const detail::SceneState> st, const void* table, std::string path);

  std::shared_ptr<const detail::SceneState> st_;
  const void* table_;  // a const toml::table*, opaque so that this header does not pull in toml++
  std::string path_;
};

// Step counts are 64-bit integers; more than 1e15 steps of dt (weeks even at a billion steps per
// second) is a typo, not a run, and would overflow the count near 9e18. Refuses `seconds` of
// simulated time at `key` of `node` past that, naming the key and the fix.
void check_step_count(const SceneNode& node, std::string_view key, double seconds, double dt);

// A body acceleration (`key` of `node`: gravity, a body force per mass) of at most 200 g (a geotechnical
// centrifuge's): a larger one is a typo, most often mm/s^2 for m/s^2, that moves grains through walls,
// or liquid out of its tank, in the first step, reported then as an instability.
void require_acceleration(const SceneNode& node, std::string_view key, const std::array<double, 3>& g);

// When on, check_all_used() also prints read_keys() to standard output, one "key: PATH" line each
// (`grainflow check --keys`; the manual's key tables are tested against it).
void report_read_keys(bool on);

// A parsed scene file plus the --set overrides applied to it, and the record of which keys were read.
// Copies share that record (they are the same document); moving is a pointer move.
class SceneDoc {
 public:
  // Parses the file, then applies overrides "dotted.path=value" in order. The value is parsed as a TOML value
  // ("2e-5", "true", "[0,0,1]", "\"text\"", "{a=1}"); if it does not parse it is taken as a bare string, and a
  // bare value replacing a string is kept as text (so `--set output.dir=2024` stays a string). Path segments may
  // index arrays as "wall.0.omega" or "wall[0].omega". An override may create a key that is absent in an existing
  // table; one whose parent table does not exist, or without '=', is a SceneError naming the override.
  static SceneDoc load(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  static SceneDoc parse(std::string_view text, const std::filesystem::path& name,
                        const std::vector<std::string>& overrides = {});  // for tests

  SceneDoc(const SceneDoc& other);
  SceneDoc& operator=(const SceneDoc& other);
  SceneDoc(SceneDoc&&) noexcept = default;
  SceneDoc& operator=(SceneDoc&&) noexcept = default;
  ~SceneDoc() = default;

  SceneNode root() const;
  const std::filesystem::path& file() const;
  // A data path (mesh, initial state) relative to the scene file's folder, so a scene runs from any directory.
  // Absolute paths are returned unchanged.
  std::filesystem::path resolve(const std::string& relative) const;

  // Every key or table that no get_*/table/maybe_table/tables call read is an unknown key: throws SceneError for the
  // first one in file order, with a fix listing the keys that table accepts and a "did you mean" when one is close.
  void check_all_used() const;

  // The scene as its systems read it, as JSON text: the file with the --set overrides applied, and every default a
  // reading call took for an absent key (summary.json's "scene_resolved"). Complete once every system has read it.
  std::string resolved_json() const;

  // Every key a reading call asked for, present in the file or not, as dotted paths with array indices
  // ("run.dt", "wall[0].omega", "fill[1].region.lo"), sorted: what this scene's systems accept.
  std::vector<std::string> read_keys() const;

 private:
  friend struct detail::SceneState;
  friend struct detail::SceneAccess;
  explicit SceneDoc(std::shared_ptr<detail::SceneState> st);

  std::shared_ptr<detail::SceneState> st_;
};

}  // namespace gf
