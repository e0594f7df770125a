// A small table of numbers read from a text file: comma-separated rows, blank lines and lines starting
// with '#' skipped, and one line of column names allowed before the first row. Used for tables a scene
// names by path (a wall's velocity table, a species' size table); a bad row is named by file and line.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace gf {

struct NumberRow {
  std::size_t line = 0;  // 1-based line in the file
  std::vector<double> values;
};

// The rows of `file`, each exactly `columns` finite numbers. `what` names the table in messages ("velocity
// table") and `layout` says what a row holds ("time, vx, vy, vz (s, m/s)"). Throws SceneError
// "<file>:<line>: <what>: <problem>. Fix: <fix>" for a file that cannot be read (at most 256 MB) or a row
// that is not `columns` numbers.
std::vector<NumberRow> read_number_table(const std::filesystem::path& file, std::size_t columns, std::string_view what,
                                         std::string_view layout);

// Throws SceneError "<file>:<line>: <problem>. Fix: <fix>" (no line when `line` is 0), the file's path cut.
[[noreturn]] void fail_number_table(const std::filesystem::path& file, std::size_t line, const std::string& problem,
                                    const std::string& fix);

class SceneNode;
class SceneError;
// A table file's error ("<file>:<line>: <problem>. Fix: <fix>") thrown again at the scene key `key` of
// `node` that named the file, its problem and fix kept.
[[noreturn]] void fail_at_key(const SceneNode& node, std::string_view key, const SceneError& e);

}  // namespace gf
