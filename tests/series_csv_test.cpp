// Time-series CSV and summary.json: exact values, rows on disk as soon as they are appended.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "systems/output/series_csv.hpp"
#include "systems/output/summary_json.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using gf::test::read_file;
using gf::test::read_lines;
using gf::test::TempDir;

namespace {

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string f; std::getline(ss, f, ',');) out.push_back(f);
  return out;
}

}  // namespace

TEST_CASE("SeriesCsv writes a header and rows that round-trip exactly", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "series.csv";
  // Hard cases for a text round trip: non-terminating binary fractions, subnormals, the
  // extremes, a negative zero, and values where %.6g or %.15g would lose bits.
  const std::vector<std::vector<double>> rows = {
      {0.0, 0.1, 1.0 / 3.0},
      {-0.0, 5e-324, std::numeric_limits<double>::max()},
      {123456789.12345679, -1e-300, std::nextafter(1.0, 2.0)},
      {2.5e-4, 0.30000000000000004, -std::numeric_limits<double>::min()},
  };
  {
    gf::SeriesCsv csv(file, {"time", "kinetic_energy", "max_overlap"});
    // The header is on disk before any row, and each row as soon as it is appended: read the
    // file while the writer is still open, as a crash would leave it.
    CHECK(read_lines(file) == std::vector<std::string>{"time,kinetic_energy,max_overlap"});
    for (std::size_t r = 0; r < rows.size(); ++r) {
      csv.append(rows[r]);
      CHECK(read_lines(file).size() == r + 2);
    }
  }

  const auto lines = read_lines(file);
  REQUIRE(lines.size() == rows.size() + 1);
  CHECK(lines[0] == "time,kinetic_energy,max_overlap");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const auto fields = split(lines[r + 1]);
    REQUIRE(fields.size() == 3);
    for (std::size_t c = 0; c < 3; ++c) {
      char* end = nullptr;
      const double parsed = std::strtod(fields[c].c_str(), &end);
      CHECK(*end == '\0');
      INFO("row " << r << " column " << c << " text " << fields[c]);
      CHECK(std::bit_cast<std::uint64_t>(parsed) == std::bit_cast<std::uint64_t>(rows[r][c]));
    }
  }
  // Shortest form, not %.17g padding: 0.1 is written as "0.1".
  CHECK(split(lines[1])[1] == "0.1");
}

TEST_CASE("SeriesCsv writes non-finite values readably", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "s.csv";
  gf::SeriesCsv csv(file, {"a", "b"});
  const double v[2] = {std::nan(""), -std::numeric_limits<double>::infinity()};
  csv.append(v);
  const auto fields = split(read_lines(file).at(1));
  REQUIRE(fields.size() == 2);
  CHECK(std::isnan(std::strtod(fields[0].c_str(), nullptr)));
  CHECK(std::strtod(fields[1].c_str(), nullptr) == -std::numeric_limits<double>::infinity());
}

TEST_CASE("SeriesCsv rejects a wrong value count without writing", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "s.csv";
  gf::SeriesCsv csv(file, {"t", "e"});
  csv.append(std::vector<double>{1.0, 2.0});
  CHECK_THROWS_AS(csv.append(std::vector<double>{1.0}), std::invalid_argument);
  CHECK_THROWS_AS(csv.append(std::vector<double>{1.0, 2.0, 3.0}), std::invalid_argument);
  CHECK(read_lines(file) == std::vector<std::string>{"t,e", "1,2"});
}

TEST_CASE("SeriesCsv truncates an old file and validates its columns", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "s.csv";
  std::ofstream(file) << "old,run\n1,2\n3,4\n";
  { gf::SeriesCsv csv(file, {"t"}); }
  CHECK(read_lines(file) == std::vector<std::string>{"t"});

  CHECK_THROWS_AS(gf::SeriesCsv(file, {}), std::invalid_argument);
  CHECK_THROWS_AS(gf::SeriesCsv(file, {"a,b"}), std::invalid_argument);
  CHECK_THROWS_AS(gf::SeriesCsv(file, {""}), std::invalid_argument);
}

TEST_CASE("SeriesCsv resumed by time keeps the rows up to that time", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "s.csv";
  // Rows at 0, 0.1, 0.2, 0.30000000000000004 (0.1 + 0.2, written as the shortest round trip),
  // then a row cut short by a kill.
  std::ofstream(file) << "t,x\n0,1\n0.1,2\n0.2,3\n0.30000000000000004,4\n0.4,";
  {
    gf::SeriesCsv csv = gf::SeriesCsv::resume_through(file, {"t", "x"}, 0.2);
    csv.append(std::vector<double>{0.25, 5.0});
  }
  CHECK(read_lines(file) == std::vector<std::string>{"t,x", "0,1", "0.1,2", "0.2,3", "0.25,5"});
  // The time compares exactly: 0.3 is below the row written at 0.1 + 0.2.
  std::ofstream(file) << "t,x\n0.1,2\n0.30000000000000004,4\n";
  { gf::SeriesCsv csv = gf::SeriesCsv::resume_through(file, {"t", "x"}, 0.3); }
  CHECK(read_lines(file) == std::vector<std::string>{"t,x", "0.1,2"});
  // A missing file (a run that wrote none) starts with its header.
  fs::remove(file);
  { gf::SeriesCsv csv = gf::SeriesCsv::resume_through(file, {"t", "x"}, 1.0); }
  CHECK(read_lines(file) == std::vector<std::string>{"t,x"});
  // Other columns are refused, and the file is left as it was.
  std::ofstream(file) << "t,y\n0,1\n";
  CHECK_THROWS_AS(gf::SeriesCsv::resume_through(file, {"t", "x"}, 1.0), std::runtime_error);
  CHECK(read_lines(file) == std::vector<std::string>{"t,y", "0,1"});
}

TEST_CASE("SeriesCsv names the file it cannot open", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "missing_folder" / "s.csv";
  try {
    gf::SeriesCsv csv(file, {"t"});
    FAIL("expected SeriesCsv to throw");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find(file.string()) != std::string::npos);
  }
}

TEST_CASE("write_summary_json writes indented JSON that parses back, atomically replaced", "[output]") {
  TempDir tmp("csv_test");
  const fs::path file = tmp.path / "summary.json";
  nlohmann::json doc = {{"scene", "drum"},
                        {"steps", 1000},
                        {"final_time", 0.1},
                        {"timings", {{"contact", 1.25}, {"integrate", 0.5}}}};
  gf::write_summary_json(file, doc);
  const std::string text = read_file(file);
  CHECK(nlohmann::json::parse(text) == doc);
  CHECK(text.find("\n  \"scene\": \"drum\"") != std::string::npos);  // indent 2
  CHECK(text.back() == '\n');

  doc["steps"] = 2000;
  gf::write_summary_json(file, doc);
  CHECK(nlohmann::json::parse(read_file(file))["steps"] == 2000);
  CHECK_FALSE(fs::exists(tmp.path / "summary.json.tmp"));

  // Invalid UTF-8 in a string is replaced, not allowed to lose the whole summary.
  gf::write_summary_json(file, nlohmann::json{{"name", std::string("caf\xe9")}});
  CHECK(nlohmann::json::parse(read_file(file)).contains("name"));
}
