// Readers for the files a run on several ranks writes, for its tests: a numeric CSV and the id
// array of a .vtp piece (raw appended binary, UInt64 headers, as vtp_bytes writes it).
#pragma once

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace gf::test {

inline std::string slurp(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

struct Csv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::size_t column(const std::string& name) const {
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c] == name) return c;
    return columns.size();
  }
};

inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string f; std::getline(s, f, ',');) out.push_back(f);
  return out;
}

inline Csv read_csv(const std::filesystem::path& file) {
  Csv csv;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return csv;
  csv.columns = split(line);
  while (std::getline(in, line)) {
    std::vector<double> row;
    for (const std::string& f : split(line)) row.push_back(std::strtod(f.c_str(), nullptr));
    csv.rows.push_back(row);
  }
  return csv;
}

// The values of attribute `name` in every element of `xml` that has it, in order.
inline std::vector<std::string> attribute_values(const std::string& xml, const std::string& name) {
  std::vector<std::string> out;
  const std::string key = " " + name + "=\"";
  for (std::size_t at = xml.find(key); at != std::string::npos; at = xml.find(key, at + 1)) {
    const std::size_t a = at + key.size();
    out.push_back(xml.substr(a, xml.find('"', a) - a));
  }
  return out;
}

// The Int64 array `name` of a .vtp piece; empty if the piece has none.
inline std::vector<std::int64_t> vtp_int64_array(const std::string& vtp, const std::string& name) {
  const std::size_t tag = vtp.find("Name=\"" + name + "\"");
  const std::size_t data = vtp.find("<AppendedData encoding=\"raw\">");
  if (tag == std::string::npos || data == std::string::npos) return {};
  const std::size_t off_at = vtp.find("offset=\"", tag) + 8;
  const std::size_t offset = std::stoull(vtp.substr(off_at, vtp.find('"', off_at) - off_at));
  const std::size_t base = vtp.find('_', data) + 1 + offset;
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, vtp.data() + base, sizeof bytes);
  std::vector<std::int64_t> out(bytes / sizeof(std::int64_t));
  if (!out.empty()) std::memcpy(out.data(), vtp.data() + base + sizeof bytes, bytes);
  return out;
}

}  // namespace gf::test
