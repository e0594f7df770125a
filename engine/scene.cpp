// Scene reader: see scene.hpp for what it promises. The one rule that shapes this file: every error is a SceneError
// whose text alone lets a user fix the scene (file, line, dotted key, problem, fix), because scene errors are read
// on a terminal after a batch job refused to start, far from this code.
#include "engine/scene.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "engine/read_file.hpp"

namespace gf {

std::string short_number(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

std::string number_text(double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  std::string s(buf, res.ptr);
  // "1e-05" -> "1e-5": scene files write exponents the short way, so messages should too.
  if (auto e = s.find('e'); e != std::string::npos) {
    std::size_t d = e + 1;
    if (d < s.size() && (s[d] == '-' || s[d] == '+')) ++d;
    std::size_t z = d;
    while (z + 1 < s.size() && s[z] == '0') ++z;
    s.erase(d, z - d);
    if (s[e + 1] == '+') s.erase(e + 1, 1);
  }
  return s;
}

void require_acceleration(const SceneNode& node, std::string_view key, const std::array<double, 3>& g) {
  const double a = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  constexpr double g0 = 9.80665;
  if (!(a <= 200 * g0))
    node.fail(key, "|" + std::string(key) + "| = " + short_number(a) + " m/s^2 is " + short_number(a / g0) +
                       " g, more than the 200 g of a geotechnical centrifuge",
              "is it in mm/s^2? Give the acceleration in m/s^2, e.g. [0, -9.81, 0] for Earth's gravity");
}

void check_step_count(const SceneNode& node, std::string_view key, double seconds, double dt) {
  if (seconds / dt > 1e15)
    node.fail(key, "gives " + short_number(seconds / dt) + " steps of run.dt = " + short_number(dt) + " s",
              "at most 1e15 steps: shorten it or lengthen run.dt");
}

namespace detail {

// Where a value that came from --set stands. toml++ gives such nodes the source position of the tiny document we
// parsed the value from (line 1), which would be a lie in a message, so their origin is kept here instead.
struct CliOrigin {
  std::string set_text;           // the override as typed, shown as "command line (--set <text>)"
  toml::source_position file_pos;  // where the replaced value stood in the file ({0,0} for a new key): file order
};

struct SceneState : std::enable_shared_from_this<SceneState> {
  std::filesystem::path file;
  std::string label;  // the file name as messages show it
  toml::table root;
  std::unordered_map<const toml::node*, CliOrigin> cli;
  // Reading marks are per node, not per dotted path: a path can be spelt several ways, a node is unique.
  mutable std::unordered_set<const toml::node*> used;
  // Key names each table was asked for, in asking order, present or not: the "accepts" list of an unknown-key fix.
  mutable std::unordered_map<const toml::table*, std::vector<std::string>> accepted;
  // The defaults reading calls took for absent keys, per table: with the file and the overrides, the scene the
  // run read (SceneDoc::resolved_json).
  mutable std::unordered_map<const toml::table*, toml::table> defaults;
  // Handed out by SceneNode::doc(). Non-owning (it would otherwise keep its own state alive forever); SceneDoc's
  // copy constructor re-derives an owning pointer through shared_from_this, so copies of it are safe.
  SceneDoc self{std::shared_ptr<SceneState>{}};
};

}  // namespace detail

namespace {

using detail::SceneState;

constexpr std::uint64_t kAfterFile = std::uint64_t{1} << 40;  // sorts command-line-only keys after all file keys


std::string fmt_int(std::int64_t v) { return std::to_string(v); }

// 1000000 -> "1_000_000": the TOML way of writing a long integer readably.
std::string fmt_int_grouped(std::int64_t v) {
  const std::string digits = std::to_string(v < 0 ? std::uint64_t(-(v + 1)) + 1 : std::uint64_t(v));
  std::string s = v < 0 ? "-" : "";
  // Appended digit by digit (not string::insert, which trips GCC 12's -Wrestrict false positive at -O2).
  for (std::size_t i = 0; i < digits.size(); ++i) {
    if (i > 0 && (digits.size() - i) % 3 == 0) s += '_';
    s += digits[i];
  }
  return s;
}

std::string type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a floating-point number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::array: return n.as_array()->is_array_of_tables() && !n.as_array()->empty()
                                            ? "an array of tables"
                                            : "an array";
    case toml::node_type::table: return "a table";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    default: return "nothing";
  }
}

// The value itself, for "got a string ("1e-5")". Only scalars: a whole table in a message is noise.
std::string show_value(const toml::node& n) {
  if (auto* s = n.as_string()) {
    return " (\"" + clipped(s->get(), 37) + "\")";
  }
  if (auto* i = n.as_integer()) return " (" + fmt_int(i->get()) + ")";
  if (auto* f = n.as_floating_point()) return " (" + number_text(f->get()) + ")";
  if (auto* b = n.as_boolean()) return b->get() ? " (true)" : " (false)";
  return "";
}

std::string got(const toml::node& n) { return type_name(n) + show_value(n); }

bool is_bare_key(std::string_view k) {
  if (k.empty()) return false;
  return std::all_of(k.begin(), k.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string key_text(std::string_view k) { return is_bare_key(k) ? std::string(k) : "\"" + std::string(k) + "\""; }

std::string join_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? key_text(key) : parent + "." + key_text(key);
}

std::string quoted_list(const std::vector<std::string>& xs) {
  std::string r;
  for (std::size_t i = 0; i < xs.size(); ++i) r += (i ? ", '" : "'") + xs[i] + "'";
  return r;
}

// "wall[1].motion" -> "wall.motion": the [[...]] header a user writes for that path.
std::string strip_indices(const std::string& path) {
  std::string r;
  int depth = 0;
  for (char c : path) {
    if (c == '[') ++depth;
    else if (c == ']') --depth;
    else if (depth == 0) r += c;
  }
  return r;
}

// How a fix names a table: where the user has to go and type.
std::string table_label(const std::string& path) {
  if (path.empty()) return "the top level of the file (before the first [section])";
  if (path.back() == ']') return "the [[" + strip_indices(path) + "]] entry " + path;
  // A table inside an array entry: the header to write drops the index, so name the entry separately.
  if (const auto close = path.rfind(']'); close != std::string::npos)
    return "[" + strip_indices(path) + "] of " + path.substr(0, close + 1);
  return "[" + path + "]";
}

std::string describe_int_range(std::int64_t lo, std::int64_t hi) {
  constexpr auto kMin = std::numeric_limits<std::int64_t>::min();
  constexpr auto kMax = std::numeric_limits<std::int64_t>::max();
  if (lo == kMin && hi == kMax) return "any integer";
  if (hi == kMax) return ">= " + fmt_int(lo);
  if (lo == kMin) return "<= " + fmt_int(hi);
  return "in [" + fmt_int(lo) + ", " + fmt_int(hi) + "]";
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return std::string(s.substr(b, e - b + 1));
}

}  // namespace

// The pieces SceneNode and SceneDoc share; a friend so that toml++ types stay out of the header.
struct detail::SceneAccess {
  static const toml::table& tbl(const SceneNode& n) { return *static_cast<const toml::table*>(n.table_); }

  static std::string location(const SceneState& st, const toml::node* n) {
    if (n) {
      if (auto it = st.cli.find(n); it != st.cli.end()) return "command line (--set " + clipped(it->second.set_text, 120) + ")";
      if (const auto line = n->source().begin.line; line > 0) return st.label + ":" + std::to_string(line);
    }
    return st.label;
  }

  [[noreturn]] static void fail_at(const SceneState& st, const toml::node* n, std::string_view path,
                                   std::string_view problem, std::string_view fix) {
    std::string msg = location(st, n);
    msg += ": key ";
    msg += gf::quoted(path, 120);
    msg += ": ";
    msg += problem;
    msg += ". Fix: ";
    msg += fix;
    throw SceneError(std::move(msg));
  }

  // File position used to order keys; values set on the command line keep the place of the value they replaced.
  static std::pair<std::uint64_t, std::uint64_t> order(const SceneState& st, const toml::node& n) {
    if (auto it = st.cli.find(&n); it != st.cli.end()) {
      const auto& p = it->second.file_pos;
      if (p.line == 0) return {kAfterFile, 0};
      return {p.line, p.column};
    }
    return {n.source().begin.line, n.source().begin.column};
  }

  // Looks a key up for a reading call: the name becomes one the table accepts, whether it is present or not.
  static const toml::node* find(const SceneNode& sn, std::string_view key) {
    const toml::table& t = tbl(sn);
    auto& names = sn.st_->accepted[&t];
    if (std::find(names.begin(), names.end(), key) == names.end()) names.emplace_back(key);
    return t.get(key);
  }

  static void mark(const SceneNode& sn, const toml::node* n) { sn.st_->used.insert(n); }

  // The default a reading call took for an absent key (non-finite numbers, "no end", are left out).
  template <class T>
  static void record_default(const SceneNode& sn, std::string_view key, T&& value) {
    sn.st_->defaults[&tbl(sn)].insert_or_assign(key, std::forward<T>(value));
  }

  [[noreturn]] static void fail_node(const SceneNode& sn, const toml::node& n, std::string_view path,
                                     std::string_view problem, std::string_view fix) {
    fail_at(*sn.st_, &n, path, problem, fix);
  }

  [[noreturn]] static void missing(const SceneNode& sn, std::string_view key) {
    // A misspelt required key ("fricton") is the likelier mistake than a forgotten one: name the key as typed.
    // Keys of up to four letters are left out: "kt" is one edit from "kn", and a table may hold both.
    const toml::table& t = tbl(sn);
    const auto& read = sn.st_->accepted[&t];
    for (auto&& [k, v] : t) {
      const std::string typed(k.str());
      if (typed.size() < 5 || std::find(read.begin(), read.end(), typed) != read.end() ||
          closest(typed, {std::string(key)}).empty())
        continue;
      fail_at(*sn.st_, &v, sn.path(typed), "unknown key " + gf::quoted(typed),
              "did you mean '" + std::string(key) + "'? It is required in " + table_label(sn.path_) +
                  ": write `" + key_text(key) + " = ...`");
    }
    fail_at(*sn.st_, &tbl(sn), sn.path(key), "missing required key '" + std::string(key) + "'",
            "add `" + key_text(key) + " = ...` to " + table_label(sn.path_));
  }

  [[noreturn]] static void wrong_type(const SceneNode& sn, const toml::node& n, std::string_view path,
                                      std::string_view key, std::string_view expected, std::string_view example) {
    std::string fix = "write it as `" + key_text(key) + " = " + std::string(example) + "`";
    // The commonest slip: a number or boolean typed in quotes.
    if (auto* s = n.as_string()) {
      try {
        auto probe = toml::parse("v = " + s->get(), std::string_view{"probe"});
        if (auto* v = probe.get("v"); v && probe.size() == 1 && !v->is_string() && !v->is_table())
          fix = "remove the quotes: `" + key_text(key) + " = " + clipped(s->get()) + "`";
      } catch (const toml::parse_error&) {
      }
    }
    fail_node(sn, n, path, "expected " + std::string(expected) + ", got " + got(n), fix);
  }

  // A number (integer or float) within r. `path`/`key` name the value for messages (an array element has its own).
  static double number(const SceneNode& sn, const toml::node& n, std::string_view path, std::string_view key,
                       Range r, std::string_view example = "1.0") {
    double v = 0.0;
    if (auto* i = n.as_integer()) v = double(i->get());
    else if (auto* f = n.as_floating_point()) v = f->get();
    else wrong_type(sn, n, path, key, "a number", example);
    // A denormal passes an interval open at 0, and then turns masses, time-step terms and forces into 0 or inf.
    if (std::fpclassify(v) == FP_SUBNORMAL)
      fail_node(sn, n, path, "value " + number_text(v) + " is below the smallest normal double (2.2e-308): no "
                "physical input is that small, so it is a typo",
                "set `" + key_text(key) + "` to a physical value in the key's unit (0 where the key allows it)");
    if (!r.contains(v))
      fail_node(sn, n, path, "value " + number_text(v) + " is out of range: it must be " + r.describe(),
                "set `" + key_text(key) + "` to a value that is " + r.describe());
    return v;
  }

  static std::vector<double> numbers(const SceneNode& sn, const toml::node& n, std::string_view key,
                                     std::string_view expected, std::string_view example) {
    const std::string p = sn.path(key);
    const toml::array* a = n.as_array();
    if (!a) wrong_type(sn, n, p, key, expected, example);
    std::vector<double> out;
    out.reserve(a->size());
    for (std::size_t i = 0; i < a->size(); ++i) {
      // An entry is named by its own path and line ("gravity[2]") but fixed through the key the user typed.
      const toml::node& e = *a->get(i);
      const std::string ep = p + "[" + std::to_string(i) + "]";
      const std::string entry = "entry " + std::to_string(i) + " (from 0) of `" + key_text(key) + "`";
      double v = 0.0;
      if (auto* iv = e.as_integer()) v = double(iv->get());
      else if (auto* fv = e.as_floating_point()) v = fv->get();
      else fail_node(sn, e, ep, "expected a number, got " + got(e),
                     "write " + entry + " as a number, e.g. `" + key_text(key) + " = " + std::string(example) + "`");
      if (!std::isfinite(v))
        fail_node(sn, e, ep, "value " + number_text(v) + " is out of range: it must be finite",
                  "set " + entry + " to a finite number");
      out.push_back(v);
    }
    return out;
  }

  static const toml::table& as_table(const SceneNode& sn, const toml::node& n, std::string_view key) {
    const std::string p = sn.path(key);
    if (auto* t = n.as_table()) return *t;
    std::string fix = "write it as a [" + strip_indices(p) + "] section or an inline table `" + key_text(key) +
                      " = { ... }`";
    if (n.is_array_of_tables()) fix = "use single brackets, [" + strip_indices(p) + "], for a single table";
    fail_node(sn, n, p, "expected a table, got " + got(n), fix);
  }

  static SceneNode child(const SceneNode& sn, const toml::table& t, std::string path) {
    return SceneNode(sn.st_, &t, std::move(path));
  }
};

using detail::SceneAccess;

// ---------------------------------------------------------------------------------------------------------------------
SceneError::SceneError(std::string msg) : std::runtime_error(printable(msg)) {}

// ---------------------------------------------------------------------------------------------------------------------
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

Range Range::any() { return {-kInf, kInf, true, true}; }
Range Range::positive() { return {0.0, kInf, true, true}; }
Range Range::non_negative() { return {0.0, kInf, false, true}; }
Range Range::closed(double lo, double hi) { return {lo, hi, false, false}; }
Range Range::open_closed(double lo, double hi) { return {lo, hi, true, false}; }

bool Range::contains(double v) const {
  if (std::isnan(v)) return false;
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::describe() const {
  const bool lo_inf = lo == -kInf && lo_open;
  const bool hi_inf = hi == kInf && hi_open;
  if (lo_inf && hi_inf) return "finite";
  if (hi_inf) return (lo_open ? "> " : ">= ") + number_text(lo);
  if (lo_inf) return (hi_open ? "< " : "<= ") + number_text(hi);
  return std::string("in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) + (hi_open ? ")" : "]");
}

// ---------------------------------------------------------------------------------------------------------------------
SceneNode::SceneNode(std::shared_ptr<const detail::SceneState> st, const void* table, std::string path)
    : st_(std::move(st)), table_(table), path_(std::move(path)) {}

bool SceneNode::has(std::string_view key) const { return SceneAccess::tbl(*this).contains(key); }

double SceneNode::get_double(std::string_view key, Range r) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  return SceneAccess::number(*this, *n, path(key), key, r);
}

double SceneNode::get_double(std::string_view key, double fallback, Range r) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) {
    if (std::isfinite(fallback)) SceneAccess::record_default(*this, key, fallback);
    return fallback;
  }
  SceneAccess::mark(*this, n);
  return SceneAccess::number(*this, *n, path(key), key, r);
}

std::int64_t SceneNode::get_int(std::string_view key, std::int64_t lo, std::int64_t hi) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  const std::string p = path(key);
  if (auto* f = n->as_floating_point()) {
    // TOML reads 1e6 and 10.0 as floats; say how to write the same count as an integer.
    const double v = f->get();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9.0e18)
      SceneAccess::fail_node(*this, *n, p, "expected an integer, got " + got(*n),
                             "write it without a decimal point or exponent: `" + key_text(key) + " = " +
                                 fmt_int_grouped(std::int64_t(v)) + "`");
  }
  const auto* i = n->as_integer();
  if (!i) SceneAccess::wrong_type(*this, *n, p, key, "an integer", "10");
  const std::int64_t v = i->get();
  if (v < lo || v > hi)
    SceneAccess::fail_node(*this, *n, p,
                           "value " + fmt_int(v) + " is out of range: it must be " + describe_int_range(lo, hi),
                           "set `" + key_text(key) + "` to an integer " + describe_int_range(lo, hi));
  return v;
}

std::int64_t SceneNode::get_int(std::string_view key, std::int64_t fallback, std::int64_t lo, std::int64_t hi) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);  // still an accepted name
    SceneAccess::record_default(*this, key, fallback);
    return fallback;
  }
  return get_int(key, lo, hi);
}

bool SceneNode::get_bool(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  const auto* b = n->as_boolean();
  if (!b) SceneAccess::wrong_type(*this, *n, path(key), key, "a boolean (true or false)", "true");
  return b->get();
}

bool SceneNode::get_bool(std::string_view key, bool fallback) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);
    SceneAccess::record_default(*this, key, fallback);
    return fallback;
  }
  return get_bool(key);
}

std::string SceneNode::get_string(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  const auto* s = n->as_string();
  if (!s) SceneAccess::wrong_type(*this, *n, path(key), key, "a string", "\"...\"");
  // No name, path or choice holds a NUL; a path would be cut short at it and name another file.
  if (s->get().find('\0') != std::string::npos)
    SceneAccess::fail_node(*this, *n, path(key), "the text contains a NUL character (\\u0000)",
                           "remove the \\u0000 from the text");
  return s->get();
}

std::string SceneNode::get_string(std::string_view key, std::string fallback) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);
    SceneAccess::record_default(*this, key, fallback);
    return fallback;
  }
  return get_string(key);
}

std::string SceneNode::get_choice(std::string_view key, std::vector<std::string> choices) const {
  const std::string v = get_string(key);
  if (std::find(choices.begin(), choices.end(), v) != choices.end()) return v;
  std::string fix = "use one of " + quoted_list(choices);
  if (auto near = closest(v, choices); !near.empty()) fix += " (did you mean '" + near + "'?)";
  SceneAccess::fail_node(*this, *SceneAccess::tbl(*this).get(key), path(key),
                         gf::quoted(v) + " is not an accepted value", fix);
}

std::string SceneNode::get_choice(std::string_view key, std::vector<std::string> choices,
                                  std::string fallback) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);
    SceneAccess::record_default(*this, key, fallback);
    return fallback;
  }
  return get_choice(key, std::move(choices));
}

std::array<double, 3> SceneNode::get_vec3(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  constexpr std::string_view kWhat = "an array of 3 numbers [x, y, z]";
  const auto v = SceneAccess::numbers(*this, *n, key, kWhat, "[0.0, 0.0, 1.0]");
  if (v.size() != 3)
    SceneAccess::fail_node(*this, *n, path(key),
                           "expected 3 numbers [x, y, z], got " + std::to_string(v.size()),
                           "write it as `" + key_text(key) + " = [x, y, z]`");
  return {v[0], v[1], v[2]};
}

std::array<double, 3> SceneNode::get_vec3(std::string_view key, std::array<double, 3> fallback) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);
    SceneAccess::record_default(*this, key, toml::array{fallback[0], fallback[1], fallback[2]});
    return fallback;
  }
  return get_vec3(key);
}

std::vector<double> SceneNode::get_doubles(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  return SceneAccess::numbers(*this, *n, key, "an array of numbers", "[1.0, 2.0]");
}

std::vector<std::array<double, 3>> SceneNode::get_vec3_list(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) SceneAccess::missing(*this, key);
  SceneAccess::mark(*this, n);
  const std::string fix = "write it as `" + key_text(key) + " = [[x, y, z], ...]`";
  const toml::array* a = n->as_array();
  if (!a || a->empty()) SceneAccess::fail_node(*this, *n, path(key), "expected a non-empty list of [x, y, z]", fix);
  std::vector<std::array<double, 3>> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const auto v = SceneAccess::numbers(*this, e, key, "an array of 3 numbers [x, y, z]", "[[0.0, 0.0, 1.0]]");
    if (v.size() != 3)
      SceneAccess::fail_node(*this, e, path(key) + "[" + std::to_string(i) + "]",
                             "expected 3 numbers [x, y, z], got " + std::to_string(v.size()), fix);
    out.push_back({v[0], v[1], v[2]});
  }
  return out;
}

SceneNode SceneNode::table(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) {
    const std::string p = path(key);
    const std::string fix = p.find('[') == std::string::npos
                                ? "add a [" + p + "] section"
                                : "add `" + key_text(key) + " = { ... }` to " + table_label(path_);
    SceneAccess::fail_at(*st_, &SceneAccess::tbl(*this), p, "missing required table [" + strip_indices(p) + "]",
                         fix);
  }
  const toml::table& t = SceneAccess::as_table(*this, *n, key);
  SceneAccess::mark(*this, n);
  return SceneAccess::child(*this, t, path(key));
}

std::optional<SceneNode> SceneNode::maybe_table(std::string_view key) const {
  if (!has(key)) {
    SceneAccess::find(*this, key);
    return std::nullopt;
  }
  return table(key);
}

bool SceneNode::holds_table(std::string_view key) const {
  const toml::node* n = SceneAccess::tbl(*this).get(key);
  return n && n->is_table();
}

std::vector<SceneNode> SceneNode::tables(std::string_view key) const {
  const toml::node* n = SceneAccess::find(*this, key);
  if (!n) return {};
  const std::string p = path(key);
  const std::string header = "[[" + strip_indices(p) + "]]";
  const toml::array* a = n->as_array();
  if (!a) {
    SceneAccess::fail_node(*this, *n, p, "expected an array of tables, got " + got(*n),
                           n->is_table() ? "use double brackets, " + header + ", once for each entry"
                                         : "write each entry as a " + header + " section");
  }
  SceneAccess::mark(*this, n);
  std::vector<SceneNode> out;
  out.reserve(a->size());
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string ep = p + "[" + std::to_string(i) + "]";
    const toml::table* t = e.as_table();
    if (!t)
      SceneAccess::fail_node(*this, e, ep, "expected a table, got " + got(e),
                             "write each entry of '" + std::string(key) + "' as a " + header +
                                 " section or an inline table { ... }");
    SceneAccess::mark(*this, t);
    out.push_back(SceneAccess::child(*this, *t, ep));
  }
  return out;
}

std::vector<std::string> SceneNode::keys() const {
  const toml::table& t = SceneAccess::tbl(*this);
  std::vector<std::pair<std::pair<std::uint64_t, std::uint64_t>, std::string>> ks;
  for (auto&& [k, v] : t) ks.emplace_back(SceneAccess::order(*st_, v), std::string(k.str()));
  // Stable: keys with equal positions (several new keys from the command line) stay in name order.
  std::stable_sort(ks.begin(), ks.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  out.reserve(ks.size());
  for (auto& e : ks) out.push_back(std::move(e.second));
  return out;
}

int SceneNode::line(std::string_view key) const {
  const toml::node* n = SceneAccess::tbl(*this).get(key);
  if (!n || st_->cli.count(n)) return 0;
  return int(n->source().begin.line);
}

int SceneNode::line() const {
  const toml::table& t = SceneAccess::tbl(*this);
  if (st_->cli.count(&t)) return 0;
  return int(t.source().begin.line);
}

std::string SceneNode::path(std::string_view key) const { return join_path(path_, key); }

void SceneNode::fail(std::string_view key, std::string_view problem, std::string_view fix) const {
  const toml::table& t = SceneAccess::tbl(*this);
  const toml::node* n = t.get(key);
  SceneAccess::fail_at(*st_, n ? n : &t, path(key), problem, fix);
}

const SceneDoc& SceneNode::doc() const { return st_->self; }

// ---------------------------------------------------------------------------------------------------------------------
namespace {

struct PathSegment {
  std::string text;
  bool bracketed;  // written as [i]: must index an array. A plain "0" indexes an array too, if it meets one.
};

[[noreturn]] void override_error(const std::string& set_text, const std::string& path, std::string_view problem,
                                 std::string_view fix) {
  throw SceneError("command line (--set " + clipped(set_text, 120) + "): key " + gf::quoted(path, 120) + ": " +
                   std::string(problem) + ". Fix: " + std::string(fix));
}

std::vector<PathSegment> split_override_path(const std::string& set_text, const std::string& path) {
  std::vector<PathSegment> segs;
  std::size_t i = 0;
  const auto bad = [&] {
    override_error(set_text, path, "the key path is malformed",
                   "write it as dotted keys with optional array indices, e.g. --set run.dt=1e-5 or "
                   "--set wall[1].omega=2");
  };
  while (i < path.size()) {
    if (path[i] == '[') {
      const auto close = path.find(']', i);
      if (close == std::string::npos || close == i + 1 || segs.empty()) bad();
      std::string idx = path.substr(i + 1, close - i - 1);
      if (!std::all_of(idx.begin(), idx.end(), [](char c) { return c >= '0' && c <= '9'; })) bad();
      segs.push_back({idx, true});
      i = close + 1;
      if (i < path.size() && path[i] != '.' && path[i] != '[') bad();
      if (i < path.size() && path[i] == '.') {
        ++i;
        if (i == path.size()) bad();
      }
      continue;
    }
    const auto end = path.find_first_of(".[", i);
    std::string key = trim(path.substr(i, end == std::string::npos ? std::string::npos : end - i));
    if (key.empty()) bad();
    segs.push_back({key, false});
    if (end == std::string::npos) break;
    i = end;
    if (path[i] == '.') {
      ++i;
      if (i == path.size()) bad();
    }
  }
  if (segs.empty()) bad();
  return segs;
}

bool parse_index(const std::string& s, std::size_t& out) {
  if (s.empty() || !std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; })) return false;
  const auto res = std::from_chars(s.data(), s.data() + s.size(), out);
  return res.ec == std::errc{} && res.ptr == s.data() + s.size();
}

std::vector<std::string> table_keys(const toml::table& t) {
  std::vector<std::string> ks;
  for (auto&& [k, v] : t) ks.emplace_back(k.str());
  return ks;
}

void forget_subtree(SceneState& st, const toml::node& n) {
  st.cli.erase(&n);
  if (auto* t = n.as_table())
    for (auto&& [k, v] : *t) forget_subtree(st, v);
  if (auto* a = n.as_array())
    for (auto& e : *a) forget_subtree(st, e);
}

void remember_subtree(SceneState& st, const toml::node& n, const detail::CliOrigin& origin) {
  st.cli[&n] = origin;
  if (auto* t = n.as_table())
    for (auto&& [k, v] : *t) remember_subtree(st, v, origin);
  if (auto* a = n.as_array())
    for (auto& e : *a) remember_subtree(st, e, origin);
}

// Applies one "--set path=value" to the parsed file.
// An override's path names a table the scene does not have (an override may add a key, not a table).
[[noreturn]] void fail_missing_table(const std::string& set_text, const std::string& path, const std::string& shown,
                                     const std::string& next_shown, const std::vector<PathSegment>& segs,
                                     const PathSegment& seg, const toml::table& parent) {
  std::string fix = "check the spelling";
  const auto ks = table_keys(parent);
  if (auto near = closest(seg.text, ks); !near.empty()) fix += " (did you mean '" + near + "'?)";
  const std::string where = shown.empty() ? "the top level" : "[" + strip_indices(shown) + "]";
  fix += ks.empty() ? "; " + where + " is empty" : "; " + where + " has " + quoted_list(ks);
  override_error(set_text, path,
                 "there is no table [" + strip_indices(next_shown) + "] in the scene to set '" + segs.back().text +
                     "' in (an override may add a key, not a table)",
                 fix);
}

// Where an override's value goes: the key `seg` of a table, or entry `index` of an array.
struct OverrideSlot {
  toml::table* table = nullptr;
  toml::array* array = nullptr;
  std::size_t index = 0;
  toml::node* existing = nullptr;
};

// Replaces or adds the value; keeps the replaced value's file position so keys() stays in file order.
void put_override_value(SceneState& st, const std::string& set_text, const std::string& value_text,
                        toml::table& parsed, const toml::node* value, const PathSegment& seg, const OverrideSlot& at) {
  detail::CliOrigin origin{set_text, {}};
  if (at.existing) {
    if (auto it = st.cli.find(at.existing); it != st.cli.end()) origin.file_pos = it->second.file_pos;
    else origin.file_pos = at.existing->source().begin;
    forget_subtree(st, *at.existing);
  }
  // A bare word replacing a string stays a string: `--set output.name=2024` must not turn the name into a number.
  const bool as_text = !value || (at.existing && at.existing->is_string() && !value->is_string());
  const auto put = [&](auto&& v) {
    if (at.table) at.table->insert_or_assign(seg.text, std::forward<decltype(v)>(v));
    else at.array->replace(at.array->cbegin() + std::ptrdiff_t(at.index), std::forward<decltype(v)>(v));
  };
  if (as_text) put(toml::value<std::string>(value_text));
  else std::move(*parsed.get("v")).visit([&](auto&& v) { put(std::move(v)); });
  const toml::node* added = at.table ? at.table->get(seg.text) : at.array->get(at.index);
  remember_subtree(st, *added, origin);
}

void apply_override(SceneState& st, const std::string& set_text) {
  const auto eq = set_text.find('=');
  if (eq == std::string::npos)
    override_error(set_text, trim(set_text), "the override has no '='",
                   "write it as --set path.to.key=value, e.g. --set run.dt=1e-5");
  const std::string path = trim(std::string_view(set_text).substr(0, eq));
  const std::string value_text = trim(std::string_view(set_text).substr(eq + 1));
  if (path.empty())
    override_error(set_text, path, "the key path before '=' is empty",
                   "write it as --set path.to.key=value, e.g. --set run.dt=1e-5");
  const std::vector<PathSegment> segs = split_override_path(set_text, path);

  // The value as TOML; anything that is not exactly one TOML value is taken as text, so that
  // `--set output.dir=runs/a` needs no shell-escaped quotes.
  toml::table parsed;
  const toml::node* value = nullptr;
  try {
    parsed = toml::parse("v = " + value_text + "\n", std::string_view{"--set"});
    if (parsed.size() == 1) value = parsed.get("v");
  } catch (const toml::parse_error&) {
  }

  toml::node* cur = &st.root;
  std::string shown;  // the path walked so far, as messages print it
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const PathSegment& seg = segs[i];
    const bool last = i + 1 == segs.size();
    OverrideSlot at{cur->as_table(), cur->as_array()};
    toml::table* parent_table = at.table;
    toml::array* parent_array = at.array;
    std::size_t& index = at.index;
    toml::node*& existing = at.existing;
    std::string next_shown;

    if (parent_table && !seg.bracketed) {
      next_shown = join_path(shown, seg.text);
      existing = parent_table->get(seg.text);
      if (!existing && !last) fail_missing_table(set_text, path, shown, next_shown, segs, seg, *parent_table);
    } else if (parent_array) {
      if (!parse_index(seg.text, index))
        override_error(set_text, path, "'" + shown + "' is an array, not a table",
                       "index it by position, e.g. " + shown + "[0]" + (last ? "" : "." + segs[i + 1].text));
      next_shown = shown + "[" + seg.text + "]";
      if (index >= parent_array->size())
        override_error(set_text, path,
                       "index " + seg.text + " is out of range: '" + shown + "' has " +
                           std::to_string(parent_array->size()) + " entries",
                       parent_array->empty() ? "'" + shown + "' is empty; add entries in the scene file"
                                             : "use an index from 0 to " + std::to_string(parent_array->size() - 1) +
                                                   " (indices start at 0)");
      existing = parent_array->get(index);
    } else {
      const std::string what = shown.empty() ? std::string("the top level") : "'" + shown + "'";
      override_error(set_text, path,
                     what + " is " + type_name(*cur) + ", so it has no " +
                         (seg.bracketed ? "entry [" + seg.text + "]" : "key '" + seg.text + "'"),
                     "check the path against the scene file");
    }

    if (!last) {
      cur = existing;
      shown = next_shown;
      continue;
    }

    put_override_value(st, set_text, value_text, parsed, value, seg, at);
    return;
  }
}

struct Unknown {
  std::pair<std::uint64_t, std::uint64_t> pos;
  const toml::node* node;
  const toml::table* parent;
  std::string key;
  std::string path;
  std::string parent_path;
};

void collect_unknown(const SceneState& st, const toml::table& t, const std::string& path, std::vector<Unknown>& out);

void collect_unknown_in_array(const SceneState& st, const toml::array& a, const std::string& path,
                              std::vector<Unknown>& out) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    if (auto* t = a.get(i)->as_table()) collect_unknown(st, *t, p, out);
    else if (auto* sub = a.get(i)->as_array()) collect_unknown_in_array(st, *sub, p, out);
  }
}

void collect_unknown(const SceneState& st, const toml::table& t, const std::string& path, std::vector<Unknown>& out) {
  for (auto&& [k, v] : t) {
    const std::string p = join_path(path, k.str());
    if (!st.used.count(&v)) {
      // Report the unread key itself, not everything under it: one unknown table is one mistake.
      out.push_back({SceneAccess::order(st, v), &v, &t, std::string(k.str()), p, path});
    } else if (auto* sub = v.as_table()) {
      collect_unknown(st, *sub, p, out);
    } else if (auto* arr = v.as_array()) {
      collect_unknown_in_array(st, *arr, p, out);
    }
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------------
SceneDoc::SceneDoc(std::shared_ptr<detail::SceneState> st) : st_(std::move(st)) {}

// Always owning, also when copying the non-owning handle that SceneNode::doc() returns.
SceneDoc::SceneDoc(const SceneDoc& other) : st_(other.st_ ? other.st_->shared_from_this() : nullptr) {}

SceneDoc& SceneDoc::operator=(const SceneDoc& other) {
  if (this != &other) st_ = other.st_ ? other.st_->shared_from_this() : nullptr;
  return *this;
}

SceneDoc SceneDoc::load(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  // A scene is a text of a few kB: 64 MB is far past any, and keeps a wrong path from filling memory.
  std::string text;
  FileProblem why;
  if (!read_regular_file(file, std::size_t(64) << 20, text, why)) {
    std::error_code ec;
    const auto cwd = std::filesystem::current_path(ec);
    throw SceneError(file.string() + ": cannot read the scene file: " + why.problem + ". Fix: " + why.fix +
                     (file.is_relative() && !ec ? " (relative paths start from " + cwd.string() + ")" : ""));
  }
  return parse(text, file, overrides);
}

SceneDoc SceneDoc::parse(std::string_view text, const std::filesystem::path& name,
                         const std::vector<std::string>& overrides) {
  auto st = std::make_shared<detail::SceneState>();
  st->file = name;
  st->label = name.string();
  try {
    st->root = toml::parse(text, std::string_view{st->label});
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    const std::string line = std::to_string(b.line), col = std::to_string(b.column);
    throw SceneError(st->label + ":" + line + ":" + col + ": TOML syntax error: " + std::string(e.description()) +
                     ". Fix: correct the TOML at line " + line + ", column " + col +
                     " (text values need quotes, sections are [name], arrays are [a, b, c], each key once per "
                     "table)");
  }
  st->self = SceneDoc(std::shared_ptr<detail::SceneState>(std::shared_ptr<detail::SceneState>{}, st.get()));
  for (const auto& o : overrides) apply_override(*st, o);
  return SceneDoc(std::move(st));
}

SceneNode SceneDoc::root() const { return SceneNode(st_->shared_from_this(), &st_->root, ""); }

const std::filesystem::path& SceneDoc::file() const { return st_->file; }

std::filesystem::path SceneDoc::resolve(const std::string& relative) const {
  const std::filesystem::path p(relative);
  if (p.is_absolute()) return p;
  return st_->file.parent_path() / p;
}

namespace {
bool g_report_read_keys = false;

void collect_read(const SceneState& st, const toml::table& t, const std::string& path, std::vector<std::string>& out);

void collect_read_in_array(const SceneState& st, const toml::array& a, const std::string& path,
                           std::vector<std::string>& out) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::string p = path + "[" + std::to_string(i) + "]";
    if (auto* t = a.get(i)->as_table()) collect_read(st, *t, p, out);
    else if (auto* sub = a.get(i)->as_array()) collect_read_in_array(st, *sub, p, out);
  }
}

void collect_read(const SceneState& st, const toml::table& t, const std::string& path, std::vector<std::string>& out) {
  if (auto it = st.accepted.find(&t); it != st.accepted.end())
    for (const auto& k : it->second) out.push_back(join_path(path, k));
  for (auto&& [k, v] : t) {
    const std::string p = join_path(path, k.str());
    if (auto* sub = v.as_table()) collect_read(st, *sub, p, out);
    else if (auto* arr = v.as_array()) collect_read_in_array(st, *arr, p, out);
  }
}
}  // namespace

void report_read_keys(bool on) { g_report_read_keys = on; }

std::vector<std::string> SceneDoc::read_keys() const {
  std::vector<std::string> out;
  collect_read(*st_, st_->root, "", out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

toml::table resolved_table(const SceneState& st, const toml::table& t);

toml::array resolved_array(const SceneState& st, const toml::array& a) {
  toml::array out;
  for (const toml::node& e : a) {
    if (auto* sub = e.as_table()) out.push_back(resolved_table(st, *sub));
    else if (auto* arr = e.as_array()) out.push_back(resolved_array(st, *arr));
    else out.push_back(e);
  }
  return out;
}

// A copy of `t` with the defaults its readers took added.
toml::table resolved_table(const SceneState& st, const toml::table& t) {
  toml::table out;
  for (auto&& [k, v] : t) {
    if (auto* sub = v.as_table()) out.insert(k, resolved_table(st, *sub));
    else if (auto* arr = v.as_array()) out.insert(k, resolved_array(st, *arr));
    else out.insert(k, v);
  }
  if (auto it = st.defaults.find(&t); it != st.defaults.end())
    for (auto&& [k, v] : it->second) out.insert(k, v);  // insert keeps a key that is present
  return out;
}

}  // namespace

std::string SceneDoc::resolved_json() const {
  std::ostringstream os;
  os << toml::json_formatter{resolved_table(*st_, st_->root)};
  return os.str();
}

void SceneDoc::check_all_used() const {
  if (g_report_read_keys)
    for (const auto& k : read_keys()) std::printf("key: %s\n", k.c_str());
  std::vector<Unknown> unknown;
  collect_unknown(*st_, st_->root, "", unknown);
  if (unknown.empty()) return;
  const Unknown& u = *std::min_element(unknown.begin(), unknown.end(),
                                       [](const Unknown& a, const Unknown& b) { return a.pos < b.pos; });
  std::vector<std::string> accepted;
  if (auto it = st_->accepted.find(u.parent); it != st_->accepted.end()) accepted = it->second;
  std::string fix = "remove it or correct the spelling";
  if (auto near = closest(u.key, accepted); !near.empty()) fix += " (did you mean '" + near + "'?)";
  fix += accepted.empty() ? "; nothing in " + table_label(u.parent_path) + " is read by this scene's systems"
                          : "; " + table_label(u.parent_path) + " accepts " + quoted_list(accepted);
  SceneAccess::fail_at(*st_, u.node, u.path, "unknown key " + gf::quoted(u.key), fix);
}

}  // namespace gf
