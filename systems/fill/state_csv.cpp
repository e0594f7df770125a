#include "systems/fill/state_csv.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include "engine/atomic_file.hpp"
#include "engine/machine_memory.hpp"
#include "engine/read_file.hpp"
#include "engine/scene.hpp"

namespace gf {
namespace {

constexpr std::string_view kHeader = "id,type,diameter,x,y,z";
constexpr std::array<std::string_view, 12> kColumns = {"id", "type", "diameter", "x",  "y",  "z",
                                                       "vx", "vy",   "vz",       "wx", "wy", "wz"};
// The headers read: the positions, then optionally the velocities, then the angular velocities.
std::string header_of(std::size_t width) {
  std::string h;
  for (std::size_t c = 0; c < width; ++c) {  // appends: GCC 12 warns (-Wrestrict) on "," + std::string
    if (c) h += ',';
    h += kColumns[c];
  }
  return h;
}

[[noreturn]] void fail(const std::filesystem::path& file, int line, const std::string& problem,
                       const std::string& fix) {
  std::string msg = shown_path(file.string());
  if (line > 0) msg += ":" + std::to_string(line);
  msg += ": " + problem + ". Fix: " + fix;
  throw StateCsvError(msg);
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

// Quoted for messages; a runaway field (a whole binary line) is cut short.

// from_chars rejects a leading '+', which other writers (and people) do produce.
std::string_view strip_plus(std::string_view s) {
  if (s.size() > 1 && s.front() == '+' && s[1] != '-') s.remove_prefix(1);
  return s;
}

std::string read_all(const std::filesystem::path& file) {
  std::string data;
  FileProblem why;
  if (!read_regular_file(file, half_of_memory(), data, why)) fail(file, 0, "state file: " + why.problem, why.fix);
  return data;
}

struct LineParser {
  const std::filesystem::path& file;
  int line;

  template <class Int>
  Int integer(std::string_view field, std::size_t column) const {
    const std::string_view s = strip_plus(field);
    Int v{};
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range) {
      fail(file, line,
           "column '" + std::string(kColumns[column]) + "' is " + gf::quoted(field) + ", out of range",
           "use a smaller whole number");
    }
    if (ec != std::errc() || end != s.data() + s.size()) {
      fail(file, line,
           "column '" + std::string(kColumns[column]) + "' is " + gf::quoted(field) +
               ", not a whole number",
           "write the " + std::string(kColumns[column]) + " as an integer such as 12");
    }
    return v;
  }

  double real(std::string_view field, std::size_t column) const {
    const std::string_view s = strip_plus(field);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec == std::errc::result_out_of_range) {
      fail(file, line,
           "column '" + std::string(kColumns[column]) + "' is " + gf::quoted(field) +
               ", out of the range of a double",
           "give the value in SI units (m)");
    }
    if (ec != std::errc() || end != s.data() + s.size()) {
      fail(file, line,
           "column '" + std::string(kColumns[column]) + "' is " + gf::quoted(field) + ", not a number",
           "write a decimal number such as 0.0015 or 1.5e-3 (SI units, m)");
    }
    return v;
  }
};

template <class T>
std::string number(T v) {
  char buf[64];
  const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
  (void)ec;  // 64 characters hold any shortest double or 64-bit integer
  return std::string(buf, end);
}

// The header's width (6, 9 or 12 columns); spaces around the commas are tolerated as in data rows.
std::size_t header_width(const std::filesystem::path& file, int line, std::string_view text) {
  std::string normalised;
  std::string_view h = text;
  for (;;) {
    const std::size_t c = h.find(',');
    normalised += trim(h.substr(0, c));
    if (c == std::string_view::npos) break;
    normalised += ',';
    h.remove_prefix(c + 1);
  }
  for (std::size_t w : {6, 9, 12})
    if (normalised == header_of(w)) return w;
  // The line itself is not shown: a wrong path may name any file, and its first line is not ours to echo.
  fail(file, line,
       "the first line is not the header '" + std::string(kHeader) + "' (optionally followed by ',vx,vy,vz' "
       "and then ',wx,wy,wz')",
       "make the first line exactly " + std::string(kHeader) +
           " (SI units: diameter and positions in m), or add the velocity columns");
}

// One data row of `width` columns, every value checked.
StateRow parse_row(const std::filesystem::path& file, int line, std::string_view text, std::size_t width) {
  std::array<std::string_view, 12> fields;
  std::size_t n_fields = 0;
  std::string_view t = text;
  for (;;) {
    const std::size_t c = t.find(',');
    if (n_fields < fields.size()) fields[n_fields] = trim(t.substr(0, c));
    ++n_fields;
    if (c == std::string_view::npos) break;
    t.remove_prefix(c + 1);
  }
  if (n_fields != width) {
    fail(file, line,
         std::to_string(n_fields) + " fields, expected " + std::to_string(width) + " (" + header_of(width) + ")",
         "give every row exactly the " + std::to_string(width) + " columns of the header, with no extra commas");
  }
  for (std::size_t c = 0; c < width; ++c)
    if (fields[c].empty()) fail(file, line, "column '" + std::string(kColumns[c]) + "' is empty", "fill in every column");

  const LineParser p{file, line};
  StateRow row{};
  row.line = line;
  row.id = p.integer<std::int64_t>(fields[0], 0);
  row.type = p.integer<std::int32_t>(fields[1], 1);
  row.diameter = p.real(fields[2], 2);
  for (int i = 0; i < 3; ++i) row.x[i] = p.real(fields[3 + i], 3 + i);
  for (std::size_t c = 6; c < width; ++c) {
    double& value = c < 9 ? row.v[c - 6] : row.w[c - 9];
    value = p.real(fields[c], c);
    if (!std::isfinite(value))
      fail(file, line, "column '" + std::string(kColumns[c]) + "' is " + gf::quoted(fields[c]) + ", not finite",
           "give finite velocities (m/s and rad/s)");
  }
  if (!std::isfinite(row.diameter) || !(row.diameter > 0.0)) {
    fail(file, line, "diameter " + std::string(fields[2]) + " is not a finite number > 0",
         "give every grain a positive diameter in m");
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(row.x[i])) {
      fail(file, line,
           "column '" + std::string(kColumns[3 + i]) + "' is " + std::string(fields[3 + i]) +
               ", positions must be finite",
           "give finite coordinates in m");
    }
  }
  return row;
}

// Ids key contact history and outputs, so a repeat is an error. Sorting (id, row) pairs finds
// repeats without a hash table; the report names the earliest line that repeats an id.
void require_unique_ids(const std::filesystem::path& file, const std::vector<StateRow>& rows) {
  std::vector<std::pair<std::int64_t, std::uint32_t>> ids(rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) ids[r] = {rows[r].id, static_cast<std::uint32_t>(r)};
  std::sort(ids.begin(), ids.end());
  std::size_t repeat = rows.size();  // earliest row whose id an earlier row already has
  std::size_t original = 0;
  for (std::size_t k = 0; k < ids.size();) {
    std::size_t e = k + 1;
    while (e < ids.size() && ids[e].first == ids[k].first) ++e;
    // Within a run of equal ids the rows are in file order: the first is the original.
    if (e - k > 1 && ids[k + 1].second < repeat) {
      repeat = ids[k + 1].second;
      original = ids[k].second;
    }
    k = e;
  }
  if (repeat != rows.size()) {
    fail(file, rows[repeat].line,
         "id " + number(rows[repeat].id) + " is already used at line " + std::to_string(rows[original].line),
         "give every grain a unique id");
  }
}

}  // namespace

std::vector<StateRow> read_state_csv(const std::filesystem::path& file) {
  const std::string data = read_all(file);
  std::string_view rest(data);
  // Spreadsheet programs put a UTF-8 byte order mark in front; it is not part of the header.
  if (rest.starts_with("\xEF\xBB\xBF")) rest.remove_prefix(3);

  std::vector<StateRow> rows;
  rows.reserve(data.size() / 48);  // rows are ~60 bytes in the usual files: no regrowth
  int line = 0;
  std::size_t width = 0;  // columns of the header; 0 before it
  while (!rest.empty()) {
    const std::size_t nl = rest.find('\n');
    const std::string_view raw = rest.substr(0, nl);
    rest.remove_prefix(nl == std::string_view::npos ? rest.size() : nl + 1);
    ++line;
    const std::string_view text = trim(raw);
    if (width == 0) {
      width = header_width(file, line, text);
    } else if (!text.empty()) {
      rows.push_back(parse_row(file, line, text, width));
    }
  }
  if (width == 0) {
    fail(file, 1, "the file is empty, expected the header '" + std::string(kHeader) + "'",
         "write the header line, then one row per grain");
  }
  require_unique_ids(file, rows);
  return rows;
}

void write_state_csv(const std::filesystem::path& file, std::span<const StateRow> rows) {
  std::string out;
  out.reserve(96 + rows.size() * 192);
  out += header_of(12);
  out += '\n';
  char buf[64];
  const auto put = [&](auto v, char sep) {
    const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, v);
    (void)ec;  // 64 characters hold any shortest double or 64-bit integer
    out.append(buf, end);
    out += sep;
  };
  for (const StateRow& r : rows) {
    put(r.id, ',');
    put(r.type, ',');
    put(r.diameter, ',');
    for (int i = 0; i < 3; ++i) put(r.x[i], ',');
    for (int i = 0; i < 3; ++i) put(r.v[i], ',');
    for (int i = 0; i < 3; ++i) put(r.w[i], i < 2 ? ',' : '\n');
  }

  // Atomically: a full disk leaves the previous file (and WriteError naming this one).
  write_file_atomic(file, out);
}

}  // namespace gf
