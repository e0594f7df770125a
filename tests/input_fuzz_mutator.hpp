// The mutations of the input fuzzer (tests/input_fuzz.hpp): odd numbers, strings, arrays and
// tables put in place of a scene's values; lines, tables and keys deleted, repeated, swapped or
// misspelt; truncation and garbage bytes; --set arguments with odd keys and values; state-CSV rows
// changed; checkpoint bytes flipped, cut or overwritten and, half the time, sealed again with a
// correct checksum so that the reader's checks behind it are reached. Every choice comes from one
// generator, so an input depends only on the seed.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace gf::fuzz {

namespace fs = std::filesystem;

// A scene of scenes/ and the state file its file fill reads (if any), as text.
struct Base {
  std::string name;      // path under scenes/, for the report
  std::string file;      // the scene's file name in the work folder
  std::string text;
  std::string csv_name;  // as the scene names it (relative to the scene's folder); "" if none
  std::string csv_text;
};

inline Base load_base(const std::string& rel) {
  const fs::path scene = fs::path(GRAINFLOW_SOURCE_DIR) / "scenes" / rel;
  Base b{rel, scene.filename().string(), test::read_file(scene), "", ""};
  std::smatch m;
  if (std::regex_search(b.text, m, std::regex("\\npath = \"([^\"]+)\""))) {
    b.csv_name = m[1];
    b.csv_text = test::read_file(scene.parent_path() / b.csv_name);
  }
  return b;
}

// The mutations. Every choice comes from one generator, so an input depends only on the seed and
// its index.
class Mutator {
 public:
  explicit Mutator(std::uint64_t seed) : rng_(seed) {}

  std::size_t below(std::size_t n) { return n ? static_cast<std::size_t>(rng_() % n) : 0; }
  bool chance(int percent) { return below(100) < static_cast<std::size_t>(percent); }
  template <class T>
  const T& pick(const std::vector<T>& v) { return v[below(v.size())]; }

  std::string number(const std::string& was = "1") {
    static const std::vector<std::string> odd = {
        "0", "-0.0", "-1", "1", "2", "0.5", "1e308", "-1e308", "1e-320", "nan", "inf", "-inf", "+inf",
        "9223372036854775807", "9223372036854775808", "-9223372036854775809", "4294967296", "2147483648",
        "1e15", "1e16", "1e100", "1e-9", "1e9", "100000000", "1e7", "123456789012345678901234567890",
        "1_000", "0x10", "0o7", "0b1", "1.", ".5", "1e", "--1", "true", "\"1\"", "[]", "{}"};
    if (chance(40)) {
      try {
        const double v = std::stod(was);
        const double scale = std::pow(10.0, static_cast<double>(below(13)) - 6.0);
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.6g", (chance(20) ? -v : v) * scale);
        std::string s = buf;
        if (s.find_first_of(".en") == std::string::npos) s += ".0";
        return s;
      } catch (const std::exception&) {
      }
    }
    return pick(odd);
  }

  std::string text() {
    static const std::vector<std::string> odd = {
        "", "/dev/zero", "/dev/null", "/", ".", "..", "/proc/self/mem", "missing.csv", "fifo", "data/",
        "../../../../etc/passwd", "scene.toml", "\\u00e9t\\u00e9", "\\u0000", "a\\u0007b", "\\u001b[31m",
        "drum", "plane", "box", "cylinder", "random", "file", "linear_spring_dashpot", "hertz_mindlin",
        "small", "large", "glass", "x y", "C:\\\\x", std::string(5000, 'q')};
    return "\"" + pick(odd) + "\"";
  }

  std::string value(const std::string& was) {
    switch (below(6)) {
      case 0: return text();
      case 1: return pick(std::vector<std::string>{"[]", "[1]", "[0,0]", "[0,0,0]", "[1,2,3,4]", "[[1]]",
                                                   "[\"a\",1]", "[nan,0,0]", "[1e308,1e308,1e308]", "[0,0,1e-320]"});
      case 2: return pick(std::vector<std::string>{"{}", "{ a = 1 }", "{ small = -1 }", "{ small = 1e9 }",
                                                   "{ 1 = \"glass\" }", "{ 7 = \"x\" }", "true", "false"});
      default: return number(was);
    }
  }

  // One change to a TOML text.
  std::string scene_text(std::string t) {
    switch (below(10)) {
      case 0: case 1: case 2: return replace_token(t, std::regex("-?[0-9][0-9_.eE+\\-]*|nan|inf"), true);
      case 3: return replace_token(t, std::regex("\"[^\"\\n]*\""), false);
      case 4: return replace_token(t, std::regex("\\[[^\\[\\]\\n]*\\]"), false);
      case 5: return line_edit(t);
      case 6: return section_edit(t);
      case 7: return insert_key(t);
      case 8: return bytes_edit(t);
      default: return rename_key(t);
    }
  }

  // One change to a state CSV.
  std::string csv_text(std::string t) {
    switch (below(6)) {
      case 0: case 1: return replace_token(t, std::regex("-?[0-9][0-9.eE+\\-]*"), true);
      case 2: return line_edit(t);
      case 3: return bytes_edit(t);
      case 4: {
        std::vector<std::string> lines = test::lines_of(t);
        if (lines.empty()) return t;
        std::string& l = lines[below(lines.size())];
        l = pick(std::vector<std::string>{l + ",1", l.substr(0, l.rfind(',')), l + "\r", "", ",,,,,",
                                          "id,type,diameter,x,y,z", "1,1,0.003,0,0,0", l + "," + l});
        return join(lines);
      }
      default: return pick(std::vector<std::string>{"", "\n", "id,type,diameter,x,y,z", t + t, t.substr(0, t.size() / 2),
                                                    "x,y,z\n1,2,3\n", std::string(3, '\0') + t});
    }
  }

  // --set arguments: a key of the scene (or a made-up path) with an odd value.
  std::vector<std::string> overrides(const std::string& text) {
    const std::vector<std::string> keys = dotted_keys(text);
    std::vector<std::string> out;
    for (std::size_t k = 0, n = 1 + below(3); k < n; ++k) {
      std::string key = keys.empty() || chance(20) ? odd_path() : pick(keys);
      std::string arg = key + "=" + value("1");
      if (chance(5)) arg = pick(std::vector<std::string>{key, "=", "=1", key + "==1", key + "= ", ""});
      out.push_back(arg);
    }
    return out;
  }

  // One change to checkpoint bytes, then (half the time) its checksum recomputed, so that the reader's
  // checks behind the checksum are reached.
  std::string checkpoint(std::string b) {
    switch (below(5)) {
      case 0: for (int k = 0, n = 1 + static_cast<int>(below(8)); k < n && !b.empty(); ++k)
          b[below(b.size())] ^= static_cast<char>(1u << below(8));
        break;
      case 1: b.resize(below(b.size() + 1)); break;
      case 2: b += std::string(1 + below(64), static_cast<char>(below(256))); break;
      case 3: {
        static const std::vector<std::uint64_t> odd = {0, 1, 7, 0xffffffffull, 0x7fffffffffffffffull, ~0ull,
                                                       1ull << 40, 1ull << 62};
        const std::uint64_t v = pick(odd);
        if (b.size() > 8) {
          const std::size_t at = below(b.size() - 8);
          std::memcpy(b.data() + at, &v, below(2) ? 4 : 8);
        }
        break;
      }
      default: for (int k = 0; k < 16 && !b.empty(); ++k) b[below(b.size())] = static_cast<char>(below(256));
    }
    if (b.size() >= 8 && chance(50)) reseal(b);
    return b;
  }

 private:
  static std::string join(const std::vector<std::string>& lines) {
    std::string t;
    for (const std::string& l : lines) t += l + "\n";
    return t;
  }

  std::string replace_token(const std::string& t, const std::regex& re, bool numeric) {
    std::vector<std::pair<std::size_t, std::size_t>> at;
    for (auto it = std::sregex_iterator(t.begin(), t.end(), re); it != std::sregex_iterator(); ++it)
      at.push_back({static_cast<std::size_t>(it->position()), static_cast<std::size_t>(it->length())});
    if (at.empty()) return t;
    const auto [pos, len] = pick(at);
    const std::string was = t.substr(pos, len);
    return t.substr(0, pos) + (numeric ? number(was) : value(was)) + t.substr(pos + len);
  }

  std::string line_edit(const std::string& t) {
    std::vector<std::string> lines = test::lines_of(t);
    if (lines.empty()) return t;
    const std::size_t i = below(lines.size()), j = below(lines.size());
    switch (below(4)) {
      case 0: lines.erase(lines.begin() + static_cast<long>(i)); break;
      case 1: lines.insert(lines.begin() + static_cast<long>(i), lines[j]); break;
      case 2: std::swap(lines[i], lines[j]); break;
      default: lines.resize(i);
    }
    return join(lines);
  }

  // Deletes or repeats a whole [table] / [[array]] section.
  std::string section_edit(const std::string& t) {
    std::vector<std::size_t> heads;
    for (std::size_t p = 0; (p = t.find("\n[", p)) != std::string::npos; ++p) heads.push_back(p + 1);
    if (heads.empty()) return t;
    const std::size_t k = below(heads.size());
    const std::size_t from = heads[k], to = k + 1 < heads.size() ? heads[k + 1] : t.size();
    const std::string sec = t.substr(from, to - from);
    return chance(50) ? t.substr(0, from) + t.substr(to) : t.substr(0, to) + sec + t.substr(to);
  }

  std::string insert_key(const std::string& t) {
    std::vector<std::size_t> ends;
    for (std::size_t p = 0; (p = t.find('\n', p)) != std::string::npos; ++p) ends.push_back(p + 1);
    if (ends.empty()) return t;
    static const std::vector<std::string> keys = {"dt", "duration", "count", "path", "omega", "radius", "seed",
                                                  "max_overlap", "allow_unstable_dt", "typo_key", "time", "l0"};
    const std::size_t at = pick(ends);
    return t.substr(0, at) + pick(keys) + " = " + value("1") + "\n" + t.substr(at);
  }

  std::string bytes_edit(const std::string& t) {
    switch (below(3)) {
      case 0: return t.substr(0, below(t.size() + 1));
      case 1: {
        std::string g;
        for (std::size_t k = 0, n = 1 + below(16); k < n; ++k) g += static_cast<char>(below(256));
        const std::size_t at = below(t.size() + 1);
        return t.substr(0, at) + g + t.substr(at);
      }
      default: {
        std::string s = t;
        if (!s.empty()) s[below(s.size())] = static_cast<char>(below(256));
        return s;
      }
    }
  }

  std::string rename_key(const std::string& t) {
    return replace_token_text(t, std::regex("\\n([a-z_]+) ="), [&](const std::string& k) {
      return pick(std::vector<std::string>{k + "s", k.substr(0, k.size() / 2), "\"" + k + "\"", k + "." + k, k});
    });
  }

  template <class F>
  std::string replace_token_text(const std::string& t, const std::regex& re, F&& f) {
    std::vector<std::smatch> all;
    for (auto it = std::sregex_iterator(t.begin(), t.end(), re); it != std::sregex_iterator(); ++it) all.push_back(*it);
    if (all.empty()) return t;
    const std::smatch& m = all[below(all.size())];
    const auto pos = static_cast<std::size_t>(m.position(1)), len = static_cast<std::size_t>(m.length(1));
    return t.substr(0, pos) + f(t.substr(pos, len)) + t.substr(pos + len);
  }

  std::string odd_path() {
    static const std::vector<std::string> paths = {
        "", ".", "a..b", "run.", "[", "wall[99].omega", "wall.-1.radius", "run.dt.x", "run.dt[0]", "fill.0.count.small",
        "fill.0.count.nobody", "species.0.density", "species[1].diameter", "settle.time", "output.picture_angles",
        "geometry.hi", "liquid.l0", "fluid.0.hi", "contact.model", "nothing", std::string(300, 'k')};
    return pick(paths);
  }

  // "table.key" for each key of the text, "name.N.key" inside the N-th [[name]].
  static std::vector<std::string> dotted_keys(const std::string& text) {
    std::vector<std::string> keys;
    std::map<std::string, int> count;
    std::string table;
    for (const std::string& l : test::lines_of(text)) {
      std::smatch m;
      if (std::regex_match(l, m, std::regex("\\[\\[([a-z_]+)\\]\\].*"))) table = m[1].str() + "." + std::to_string(count[m[1]]++);
      else if (std::regex_match(l, m, std::regex("\\[([a-z_.]+)\\].*"))) table = m[1];
      else if (std::regex_match(l, m, std::regex("([a-z_0-9]+) *=.*"))) keys.push_back(table.empty() ? m[1].str() : table + "." + m[1].str());
    }
    return keys;
  }

  static void reseal(std::string& b) {
    std::uint64_t h = 1469598103934665603ull;  // FNV-1a 64, as engine/checkpoint_file.cpp seals
    for (std::size_t k = 0; k + 8 < b.size(); ++k) {
      h ^= static_cast<unsigned char>(b[k]);
      h *= 1099511628211ull;
    }
    std::memcpy(b.data() + b.size() - 8, &h, 8);
  }

  std::mt19937_64 rng_;
};

}  // namespace gf::fuzz
