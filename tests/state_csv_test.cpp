// Grain-state CSV: exact round trip, the shared seed state, and errors that point at the line.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "systems/fill/state_csv.hpp"
#include "tests/test_support.hpp"

using gf::StateCsvError;
using gf::StateRow;
namespace fs = std::filesystem;

namespace {

// A file holding `content` in a fresh temporary folder, removed with the folder afterwards.
struct TempFile {
  gf::test::TempDir dir;
  fs::path path;
  explicit TempFile(const std::string& content, const std::string& stem = "state")
      : dir(stem), path(dir.write(stem + ".csv", content)) {}
};

// The message of the StateCsvError that reading the file throws ("" when none is thrown).
std::string error_for(const fs::path& p) {
  try {
    gf::read_state_csv(p);
  } catch (const StateCsvError& e) {
    return e.what();
  }
  return "";
}
std::string error_for(const TempFile& f) { return error_for(f.path); }

bool contains(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("state CSV round trip is exact", "[fill]") {
  std::vector<StateRow> rows{
      {1, 1, 1e-3, {0.1, -0.2, 1.0 / 3.0}, 0, {0.0289, -1.4e-4, 4.6e-6}, {-31.7, 0.25, 1e-12}},
      {std::numeric_limits<std::int64_t>::max(), 2, 3e-3, {-0.0, 1e-300, 4.9e-324}, 0},
      {std::numeric_limits<std::int64_t>::min(), -5, 0.1 + 0.2, {1.7976931348623157e308, 2.5e-7, -3.14159}, 0},
      {42, 0, std::nextafter(1e-3, 1.0), {std::nextafter(0.0, 1.0), 123456.789, -1e-9}, 0},
  };
  const TempFile f("", "roundtrip");
  gf::write_state_csv(f.path, rows);
  const auto back = gf::read_state_csv(f.path);
  REQUIRE(back.size() == rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    CHECK(back[k].id == rows[k].id);
    CHECK(back[k].type == rows[k].type);
    CHECK(back[k].diameter == rows[k].diameter);
    for (int i = 0; i < 3; ++i) {
      CHECK(back[k].x[i] == rows[k].x[i]);
      CHECK(std::signbit(back[k].x[i]) == std::signbit(rows[k].x[i]));
      CHECK(back[k].v[i] == rows[k].v[i]);
      CHECK(back[k].w[i] == rows[k].w[i]);
    }
    CHECK(back[k].line == static_cast<int>(k) + 2);
  }
  CHECK_FALSE(fs::exists(fs::path(f.path.string() + ".tmp")));
}

TEST_CASE("state CSV with velocities: the shared flowing drum state loads, spins optional", "[fill]") {
  // LIGGGHTS's state at 1.5 s of rotation: positions and velocities, no spins (the data README).
  const auto rows = gf::read_state_csv(std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/data/drum_flowing_t1.5s_47108.csv");
  REQUIRE(rows.size() == 47108);
  CHECK(rows[0].id == 1);
  CHECK(rows[0].v[0] == 0.0288975);
  CHECK(rows[0].v[1] == -0.000136485);
  CHECK(rows[0].w == std::array<double, 3>{});
  double mean_speed = 0;
  for (const StateRow& r : rows) mean_speed += std::hypot(r.v[0], r.v[1], r.v[2]) / rows.size();
  CHECK(mean_speed == Approx(0.0289).epsilon(0.01));  // the data README's mean |v|, to its 3 digits
  // A header with velocities but a row without them is refused at that row.
  const TempFile f("id,type,diameter,x,y,z,vx,vy,vz\n1,1,0.001,0,0,0,1,2,3\n2,1,0.001,0.01,0,0\n", "short_row");
  try {
    gf::read_state_csv(f.path);
    FAIL("accepted a short row");
  } catch (const gf::StateCsvError& e) {
    CHECK(contains(e.what(), ":3: 6 fields, expected 9 (id,type,diameter,x,y,z,vx,vy,vz)"));
  }
}

TEST_CASE("the seed drum state loads", "[fill]") {
  const fs::path file = GRAINFLOW_SOURCE_DIR "/scenes/data/drum_settled_47108.csv";
  const auto rows = gf::read_state_csv(file);
  REQUIRE(rows.size() == 47108);
  std::size_t big = 0;
  std::size_t small = 0;
  for (const StateRow& r : rows) {
    if (r.type == 2) {
      ++big;
      CHECK(r.diameter == 3e-3);
    } else {
      REQUIRE(r.type == 1);
      ++small;
      REQUIRE(r.diameter == 1e-3);
    }
    // Inside the drum (radius 0.075 m, end walls at z = +-0.004 m). The settled state rests with
    // wall overlaps of up to ~3e-5 m (1 % of a big grain's diameter), so the bound is 5e-5 m:
    // loose enough for that, tight enough to catch swapped columns or a unit slip.
    const double rr = std::hypot(r.x[0], r.x[1]);
    REQUIRE(rr + 0.5 * r.diameter <= 0.075 + 5e-5);
    REQUIRE(std::abs(r.x[2]) + 0.5 * r.diameter <= 0.004 + 5e-5);
  }
  CHECK(big == 1682);
  CHECK(small == 45426);
  CHECK(rows.front().line == 2);
  CHECK(rows.back().line == 47109);
}

TEST_CASE("state CSV tolerates CRLF, spaces and blank lines", "[fill]") {
  const TempFile f(" id , type,diameter,x,y,z \r\n1, 1 ,0.001,+1e-3,-2e-3,0\r\n\r\n2,2,3e-3,0,0,0.5\r\n\n");
  const auto rows = gf::read_state_csv(f.path);
  REQUIRE(rows.size() == 2);
  CHECK(rows[0].x[0] == 1e-3);
  CHECK(rows[1].line == 4);
  CHECK(rows[1].x[2] == 0.5);

  const TempFile header_only("id,type,diameter,x,y,z\n");
  CHECK(gf::read_state_csv(header_only.path).empty());
}

TEST_CASE("bad state files name the file, the line and the problem", "[fill]") {
  SECTION("missing file") {
    const fs::path p = fs::temp_directory_path() / "grainflow_no_such_state_file.csv";
    const std::string m = error_for(p);
    CHECK(contains(m, p.string()));
    CHECK(contains(m, "does not exist"));
    CHECK(contains(m, "Fix:"));
  }
  SECTION("a device, a pipe or a folder is not read") {
    // /dev/zero never ends and a FIFO blocks until a writer comes: both used to be read.
    const fs::path fifo = fs::temp_directory_path() / ("grainflow_state_fifo_" + std::to_string(::getpid()));
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    for (const fs::path& p : {fs::path("/dev/zero"), fifo, fs::temp_directory_path()}) {
      INFO(p);
      const std::string m = error_for(p);
      CHECK(contains(m, p.string()));
      CHECK((contains(m, "not a regular file") || contains(m, "a folder")));
      CHECK(contains(m, "Fix:"));
    }
    fs::remove(fifo);
  }
  SECTION("wrong header") {
    const TempFile f("id,type,radius,x,y,z\n1,1,0.001,0,0,0\n");
    const std::string m = error_for(f);
    CHECK(contains(m, f.path.string() + ":1:"));
    CHECK(contains(m, "the first line is not the header 'id,type,diameter,x,y,z'"));
    CHECK_FALSE(contains(m, "radius"));  // the file's own line is not echoed (it may be any file)
  }
  SECTION("extra column in the header") {
    const TempFile f("id,type,diameter,x,y,z,vx\n");
    CHECK(contains(error_for(f), ":1: the first line is not the header"));
  }
  SECTION("a long field is shown cut") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,0.002," + std::string(100000, '9') + "x,0,0\n");
    const std::string m = error_for(f);
    CHECK(m.size() < 600);
    CHECK(contains(m, "...'"));
  }
  SECTION("empty file") {
    const TempFile f("");
    CHECK(contains(error_for(f), ":1: the file is empty"));
  }
  SECTION("not a number in column x") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,0.001,0,0,0\n2,1,0.001,abc,0,0\n");
    const std::string m = error_for(f);
    CHECK(contains(m, f.path.string() + ":3:"));
    CHECK(contains(m, "column 'x'"));
    CHECK(contains(m, "'abc', not a number"));
    CHECK(contains(m, "Fix:"));
  }
  SECTION("trailing garbage after a number") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,0.001,0,0.5m,0\n");
    CHECK(contains(error_for(f), ":2: column 'y' is '0.5m', not a number"));
  }
  SECTION("id that is not an integer") {
    const TempFile f("id,type,diameter,x,y,z\n1.5,1,0.001,0,0,0\n");
    CHECK(contains(error_for(f), ":2: column 'id' is '1.5', not a whole number"));
  }
  SECTION("wrong field count") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,0.001,0,0,0\n2,1,0.001,0,0\n");
    const std::string m = error_for(f);
    CHECK(contains(m, ":3: 5 fields, expected 6"));
  }
  SECTION("negative diameter") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,-0.001,0,0,0\n");
    const std::string m = error_for(f);
    CHECK(contains(m, f.path.string() + ":2:"));
    CHECK(contains(m, "diameter -0.001 is not a finite number > 0"));
  }
  SECTION("zero and infinite diameter") {
    const TempFile zero("id,type,diameter,x,y,z\n1,1,0,0,0,0\n");
    CHECK(contains(error_for(zero), ":2: diameter 0 is not"));
    const TempFile inf("id,type,diameter,x,y,z\n1,1,inf,0,0,0\n");
    CHECK(contains(error_for(inf), ":2: diameter inf is not"));
  }
  SECTION("non-finite position") {
    const TempFile f("id,type,diameter,x,y,z\n1,1,0.001,0,0,0\n2,1,0.001,0,0,nan\n");
    CHECK(contains(error_for(f), ":3: column 'z' is nan, positions must be finite"));
  }
  SECTION("duplicate id") {
    const TempFile f(
        "id,type,diameter,x,y,z\n7,1,0.001,0,0,0\n8,1,0.001,0,0,0\n9,1,0.001,0,0,0\n"
        "8,1,0.001,0,0,0\n7,1,0.001,0,0,0\n");
    const std::string m = error_for(f);
    CHECK(contains(m, f.path.string() + ":5: id 8 is already used at line 3"));
    CHECK(contains(m, "unique"));
  }
}
