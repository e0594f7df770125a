// VTK frame output and the atomic writes under it: the .vtp is parsed back byte by byte, so a
// wrong offset, byte count or array order fails here rather than as a blank ParaView window.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "engine/atomic_file.hpp"
#include "engine/grains.hpp"
#include "systems/output/vtk_frames.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using gf::test::read_file;
using gf::test::TempDir;

namespace {

// Values with full 53-bit mantissas, so any float conversion or text round trip would show.
gf::Grains make_grains(std::size_t n) {
  gf::Grains g;
  g.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double k = static_cast<double>(i);
    g.pos.x[i] = 0.1 * k + 1.0 / 3.0;
    g.pos.y[i] = -0.2 * k - std::sqrt(2.0) * 1e-9;
    g.pos.z[i] = std::nextafter(0.05 * k, 1.0);
    g.vel.x[i] = 1.5 * k;
    g.vel.y[i] = -2.0;
    g.vel.z[i] = 0.25 * k * k;
    g.omega.x[i] = 10.0 + k;
    g.omega.y[i] = -k;
    g.omega.z[i] = std::acos(-1.0) * k;
    g.force.x[i] = k;
    g.force.y[i] = 2.0 * k;
    g.force.z[i] = -9.81;
    g.wall_force.x[i] = 0.5;
    g.wall_force.y[i] = 0.0;
    g.wall_force.z[i] = 9.81 * k;
    g.radius.r[i] = 1e-3 * (1.0 + 0.1 * k);
    g.species.type[i] = static_cast<std::int32_t>(i % 2);
    g.pid.id[i] = 1000000000000LL + 7 * static_cast<std::int64_t>(i);
  }
  return g;
}

std::string attr(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const auto b = tag.find(key);
  if (b == std::string::npos) return {};
  const auto s = b + key.size();
  return tag.substr(s, tag.find('"', s) - s);
}

struct Array {
  std::string type;
  int components = 0;
  std::uint64_t offset = 0;
  std::string bytes;  // the block's payload, after its UInt64 byte count
};

struct Vtp {
  std::string xml;  // everything before the appended data
  std::map<std::string, Array> arrays;
  std::size_t points = 0;
};

std::size_t type_size(const std::string& t) {
  if (t == "Float64" || t == "Int64") return 8;
  if (t == "Int32") return 4;
  FAIL("unexpected DataArray type " << t);
  return 0;
}

// Reads a .vtp the way VTK's XML reader does: DataArray tags give type and offset, the block at
// '_' + offset starts with a UInt64 byte count. Also checks the blocks tile the appended data
// exactly, which is what an off-by-one in an offset would break.
Vtp parse_vtp(const std::string& doc) {
  Vtp v;
  const std::string open = "<AppendedData encoding=\"raw\">";
  const auto a = doc.find(open);
  REQUIRE(a != std::string::npos);
  v.xml = doc.substr(0, a);
  const auto underscore = doc.find('_', a + open.size());
  REQUIRE(underscore != std::string::npos);
  const std::size_t base = underscore + 1;
  const std::string close = "\n  </AppendedData>\n</VTKFile>\n";
  REQUIRE(doc.size() >= base + close.size());
  REQUIRE(doc.compare(doc.size() - close.size(), close.size(), close) == 0);
  const std::size_t data_end = doc.size() - close.size() - base;

  const auto piece = v.xml.find("<Piece ");
  REQUIRE(piece != std::string::npos);
  const std::string piece_tag = v.xml.substr(piece, v.xml.find('>', piece) - piece);
  v.points = std::stoull(attr(piece_tag, "NumberOfPoints"));
  CHECK(attr(piece_tag, "NumberOfVerts") == attr(piece_tag, "NumberOfPoints"));

  std::vector<std::pair<std::uint64_t, std::uint64_t>> extents;  // offset, block length
  for (auto p = v.xml.find("<DataArray "); p != std::string::npos; p = v.xml.find("<DataArray ", p + 1)) {
    const std::string tag = v.xml.substr(p, v.xml.find("/>", p) - p);
    Array arr;
    arr.type = attr(tag, "type");
    arr.components = std::stoi(attr(tag, "NumberOfComponents"));
    CHECK(attr(tag, "format") == "appended");
    arr.offset = std::stoull(attr(tag, "offset"));
    REQUIRE(arr.offset + 8 <= data_end);
    std::uint64_t count = 0;
    std::memcpy(&count, doc.data() + base + arr.offset, 8);
    REQUIRE(arr.offset + 8 + count <= data_end);
    CHECK(count == v.points * static_cast<std::size_t>(arr.components) * type_size(arr.type));
    arr.bytes = doc.substr(base + arr.offset + 8, count);
    extents.emplace_back(arr.offset, 8 + count);
    const std::string name = attr(tag, "Name");
    REQUIRE(v.arrays.count(name) == 0);
    v.arrays[name] = std::move(arr);
  }
  std::sort(extents.begin(), extents.end());
  std::uint64_t at = 0;
  for (const auto& [off, len] : extents) {
    CHECK(off == at);
    at = off + len;
  }
  CHECK(at == data_end);
  return v;
}

template <class T>
std::vector<T> values(const Array& a) {
  REQUIRE(a.bytes.size() % sizeof(T) == 0);
  std::vector<T> out(a.bytes.size() / sizeof(T));
  std::memcpy(out.data(), a.bytes.data(), a.bytes.size());
  return out;
}

// Bit-exact: memcmp, not ==, so -0.0 vs 0.0 or a rounding in the last place would fail.
void check_bits(const std::vector<double>& got, const std::vector<double>& want) {
  REQUIRE(got.size() == want.size());
  CHECK(std::memcmp(got.data(), want.data(), got.size() * sizeof(double)) == 0);
}

std::vector<fs::path> leftover_tmp(const fs::path& dir) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().extension() == ".tmp") out.push_back(e.path());
  return out;
}

}  // namespace

TEST_CASE("vtp frame round-trips positions, ids and fields bit-exactly", "[output]") {
  const gf::Grains g = make_grains(5);
  gf::FrameFields fields;
  fields.force = true;
  const std::string doc = gf::vtp_bytes(g, fields);
  const Vtp v = parse_vtp(doc);

  CHECK(v.xml.find("<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
                   "header_type=\"UInt64\">") != std::string::npos);
  CHECK(v.xml.find("NumberOfPoints=\"5\"") != std::string::npos);
  for (const char* tag : {"</PointData>", "</Points>", "</Verts>", "</Piece>", "</PolyData>"})
    CHECK(v.xml.find(tag) != std::string::npos);
  REQUIRE(v.points == 5);

  std::vector<double> pos, vel, speed, omega, force, radius, diameter;
  std::vector<std::int64_t> conn, offs;
  for (std::size_t i = 0; i < 5; ++i) {
    pos.insert(pos.end(), {g.pos.x[i], g.pos.y[i], g.pos.z[i]});
    vel.insert(vel.end(), {g.vel.x[i], g.vel.y[i], g.vel.z[i]});
    speed.push_back(std::sqrt(g.vel.x[i] * g.vel.x[i] + g.vel.y[i] * g.vel.y[i] + g.vel.z[i] * g.vel.z[i]));
    omega.insert(omega.end(), {g.omega.x[i], g.omega.y[i], g.omega.z[i]});
    force.insert(force.end(), {g.force.x[i] + g.wall_force.x[i], g.force.y[i] + g.wall_force.y[i],
                               g.force.z[i] + g.wall_force.z[i]});
    radius.push_back(g.radius.r[i]);
    diameter.push_back(2.0 * g.radius.r[i]);
    conn.push_back(static_cast<std::int64_t>(i));
    offs.push_back(static_cast<std::int64_t>(i + 1));
  }

  REQUIRE(v.arrays.count("Points"));
  CHECK(v.arrays.at("Points").type == "Float64");
  CHECK(v.arrays.at("Points").components == 3);
  check_bits(values<double>(v.arrays.at("Points")), pos);

  REQUIRE(v.arrays.count("id"));
  CHECK(v.arrays.at("id").type == "Int64");
  const auto ids = values<std::int64_t>(v.arrays.at("id"));
  REQUIRE(ids.size() == 5);
  for (std::size_t i = 0; i < 5; ++i) CHECK(ids[i] == g.pid.id[i]);

  REQUIRE(v.arrays.count("species"));
  CHECK(v.arrays.at("species").type == "Int32");
  const auto species = values<std::int32_t>(v.arrays.at("species"));
  REQUIRE(species.size() == 5);
  for (std::size_t i = 0; i < 5; ++i) CHECK(species[i] == g.species.type[i]);  // from 0, in [[species]] order

  check_bits(values<double>(v.arrays.at("radius")), radius);
  check_bits(values<double>(v.arrays.at("diameter")), diameter);
  CHECK(v.arrays.at("velocity").components == 3);
  check_bits(values<double>(v.arrays.at("velocity")), vel);
  check_bits(values<double>(v.arrays.at("speed")), speed);
  check_bits(values<double>(v.arrays.at("angular_velocity")), omega);
  check_bits(values<double>(v.arrays.at("force")), force);

  REQUIRE(v.arrays.count("connectivity"));
  REQUIRE(v.arrays.count("offsets"));
  CHECK(values<std::int64_t>(v.arrays.at("connectivity")) == conn);
  CHECK(values<std::int64_t>(v.arrays.at("offsets")) == offs);
}

TEST_CASE("vtp frame honours FrameFields and writes only owned rows", "[output]") {
  gf::Grains g = make_grains(5);
  g.n_owned = 3;  // rows 3 and 4 stand in for ghosts
  gf::FrameFields fields;
  fields.velocity = false;
  fields.angular_velocity = false;
  fields.force = false;
  const Vtp v = parse_vtp(gf::vtp_bytes(g, fields));
  CHECK(v.points == 3);
  CHECK(v.arrays.count("velocity") == 0);
  CHECK(v.arrays.count("speed") == 0);
  CHECK(v.arrays.count("angular_velocity") == 0);
  CHECK(v.arrays.count("force") == 0);
  for (const char* name : {"Points", "id", "species", "radius", "diameter", "connectivity", "offsets"})
    CHECK(v.arrays.count(name) == 1);
  const auto ids = values<std::int64_t>(v.arrays.at("id"));
  REQUIRE(ids.size() == 3);
  CHECK(ids[2] == g.pid.id[2]);
}

TEST_CASE("vtp frame of an empty table is still a valid document", "[output]") {
  gf::Grains g;
  const Vtp v = parse_vtp(gf::vtp_bytes(g, {}));
  CHECK(v.points == 0);
  CHECK(v.arrays.at("Points").bytes.empty());
}

TEST_CASE("FrameSeries writes frames and a pvd that lists every complete frame", "[output]") {
  TempDir tmp("vtk_test");
  gf::Grains g = make_grains(5);
  gf::FrameSeries series(tmp.path / "run");
  CHECK(series.count() == 0);

  const fs::path f0 = series.write(g, 0.0);
  CHECK(series.count() == 1);
  std::string pvd = read_file(tmp.path / "run" / "frames.pvd");
  CHECK(pvd.find("file=\"frames/frame_000000.vtp\"") != std::string::npos);
  CHECK(pvd.find("frame_000001") == std::string::npos);

  g.pos.x[0] = 42.0;
  const fs::path f1 = series.write(g, 0.0025);
  CHECK(series.count() == 2);
  CHECK(f0 == tmp.path / "run" / "frames" / "frame_000000.vtp");
  CHECK(f1 == tmp.path / "run" / "frames" / "frame_000001.vtp");

  pvd = read_file(series.pvd_path());
  CHECK(pvd.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"", 0) == 0);
  CHECK(pvd.find("<DataSet timestep=\"0\" group=\"\" part=\"0\" file=\"frames/frame_000000.vtp\"/>") !=
        std::string::npos);
  CHECK(pvd.find("<DataSet timestep=\"0.0025\" group=\"\" part=\"0\" file=\"frames/frame_000001.vtp\"/>") !=
        std::string::npos);
  CHECK(pvd.find("</Collection>") != std::string::npos);
  const std::string end = "</VTKFile>\n";
  REQUIRE(pvd.size() >= end.size());
  CHECK(pvd.compare(pvd.size() - end.size(), end.size(), end) == 0);
  // Exactly two entries: nothing stale, nothing duplicated.
  std::size_t datasets = 0;
  for (auto p = pvd.find("<DataSet "); p != std::string::npos; p = pvd.find("<DataSet ", p + 1)) ++datasets;
  CHECK(datasets == 2);

  // Every frame the .pvd names exists, is complete, and holds the state at its write.
  const Vtp v0 = parse_vtp(read_file(f0));
  const Vtp v1 = parse_vtp(read_file(f1));
  CHECK(values<double>(v0.arrays.at("Points"))[0] == make_grains(5).pos.x[0]);
  CHECK(values<double>(v1.arrays.at("Points"))[0] == 42.0);

  CHECK(leftover_tmp(tmp.path).empty());
}

TEST_CASE("FrameSeries rejects a non-finite time without advancing", "[output]") {
  TempDir tmp("vtk_test");
  gf::FrameSeries series(tmp.path);
  const gf::Grains g = make_grains(2);
  CHECK_THROWS_AS(series.write(g, std::nan("")), std::invalid_argument);
  CHECK(series.count() == 0);
  series.write(g, 1.0);
  CHECK(series.count() == 1);
  CHECK(fs::exists(tmp.path / "frames" / "frame_000000.vtp"));
}

TEST_CASE("write_file_atomic replaces content and leaves no temporary", "[output]") {
  TempDir tmp("vtk_test");
  const fs::path p = tmp.path / "state.bin";
  gf::write_file_atomic(p, "first version, longer than the second");
  CHECK(read_file(p) == "first version, longer than the second");
  gf::write_file_atomic(p, "second");
  CHECK(read_file(p) == "second");
  CHECK(leftover_tmp(tmp.path).empty());

  // A stale .tmp left by a run killed mid-write must not get in the way of the next write.
  std::ofstream(tmp.path / "state.bin.tmp") << "junk from a killed run";
  gf::write_file_atomic(p, std::string("with\0nul", 8));
  CHECK(read_file(p) == std::string("with\0nul", 8));
  CHECK(leftover_tmp(tmp.path).empty());
}

TEST_CASE("write_file_atomic names the path when it fails", "[output]") {
  TempDir tmp("vtk_test");
  const fs::path p = tmp.path / "no_such_folder" / "summary.json";
  try {
    gf::write_file_atomic(p, "x");
    FAIL("expected write_file_atomic to throw");
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    CHECK(what.find(p.string()) != std::string::npos);
    CHECK(what.find("No such file or directory") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(p));
}

TEST_CASE("ensure_directory creates parents and rejects a file in the way", "[output]") {
  TempDir tmp("vtk_test");
  const fs::path nested = tmp.path / "a" / "b" / "c";
  gf::ensure_directory(nested);
  CHECK(fs::is_directory(nested));
  gf::ensure_directory(nested);  // existing folder: no error

  const fs::path file = tmp.path / "plain_file";
  std::ofstream(file) << "x";
  try {
    gf::ensure_directory(file);
    FAIL("expected ensure_directory to throw");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()).find(file.string()) != std::string::npos);
  }
  CHECK_THROWS_AS(gf::ensure_directory(file / "sub"), std::runtime_error);
  // The FrameSeries constructor goes through ensure_directory, so a bad --out fails up front.
  CHECK_THROWS_AS(gf::FrameSeries(file), std::runtime_error);
}
