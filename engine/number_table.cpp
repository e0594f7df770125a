#include "engine/number_table.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "engine/read_file.hpp"
#include "engine/scene.hpp"
#include "engine/user_text.hpp"

namespace gf {

namespace {

constexpr std::size_t kMaxTableBytes = std::size_t(1) << 28;  // 256 MB: millions of rows, never all memory

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// The fields of a line split at commas, each parsed whole as a finite number; false if one is not.
bool parse_row(std::string_view line, std::vector<double>& out) {
  out.clear();
  while (true) {
    const std::size_t comma = line.find(',');
    const std::string_view f = trim_blanks(line.substr(0, comma));
    double v = 0.0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (f.empty() || ec != std::errc{} || end != f.data() + f.size() || !std::isfinite(v)) return false;
    out.push_back(v);
    if (comma == std::string_view::npos) return true;
    line.remove_prefix(comma + 1);
  }
}

}  // namespace

void fail_number_table(const std::filesystem::path& file, std::size_t line, const std::string& problem,
                       const std::string& fix) {
  std::string msg = shown_path(file.string());
  if (line > 0) msg += ":" + std::to_string(line);
  throw SceneError(msg + ": " + problem + ". Fix: " + fix);
}

void fail_at_key(const SceneNode& node, std::string_view key, const SceneError& e) {
  const std::string m = e.what();
  const std::size_t at = m.rfind(". Fix: ");
  if (at == std::string::npos) node.fail(key, m, "correct the file, or the path (relative to the scene file)");
  node.fail(key, m.substr(0, at), m.substr(at + 7));
}

std::vector<NumberRow> read_number_table(const std::filesystem::path& file, std::size_t columns, std::string_view what,
                                         std::string_view layout) {
  const std::string name(what);
  std::string data;
  FileProblem why;
  if (!read_regular_file(file, kMaxTableBytes, data, why)) fail_number_table(file, 0, name + ": " + why.problem, why.fix);
  std::vector<NumberRow> rows;
  std::vector<double> row;
  std::size_t line_no = 0;
  bool header_seen = false;
  for (std::size_t at = 0; at < data.size();) {
    const std::size_t end = std::min(data.find('\n', at), data.size());
    const std::string_view line = trim_blanks(std::string_view(data).substr(at, end - at));
    at = end + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    if (!parse_row(line, row)) {
      if (!header_seen && rows.empty()) {  // a header line of names
        header_seen = true;
        continue;
      }
      fail_number_table(file, line_no, name + ": the row " + quoted(line) + " is not " + std::to_string(columns) + " numbers",
                        "give each row as " + std::string(layout) + ", separated by commas");
    }
    if (row.size() != columns)
      fail_number_table(file, line_no,
                        name + ": the row has " + std::to_string(row.size()) + " numbers, not " + std::to_string(columns),
                        "give each row as " + std::string(layout));
    rows.push_back({line_no, row});
  }
  return rows;
}

}  // namespace gf
