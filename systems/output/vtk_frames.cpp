#include "systems/output/vtk_frames.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "engine/atomic_file.hpp"
#include "systems/output/vtk_appended.hpp"

namespace gf {
namespace {

using vtk::AppendedArrays;
using vtk::kByteOrder;
using vtk::shortest;

}  // namespace

std::string vtp_bytes(const Grains& g, const FrameFields& fields, std::span<const PointScalars> extra) {
  const std::size_t n = g.n_owned;
  AppendedArrays data;
  std::string xml;
  xml.reserve(2048);

  xml += "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"";
  xml += kByteOrder;
  xml += "\" header_type=\"UInt64\">\n";
  xml += "  <PolyData>\n";
  const std::string ns = std::to_string(n);
  xml += "    <Piece NumberOfPoints=\"" + ns + "\" NumberOfVerts=\"" + ns +
         "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n";

  // Scalars/Vectors pick what ParaView colours by and feeds to Glyph when the file opens.
  xml += "      <PointData Scalars=\"radius\"";
  if (fields.velocity) xml += " Vectors=\"velocity\"";
  xml += ">\n";
  const std::string_view in = "        ";
  data.add<std::int64_t>(xml, in, "id", 1, n, [&](std::size_t i, std::size_t) { return g.pid.id[i]; });
  // Species as every output and message numbers them: 0-based, in [[species]] order (`species.0` in --set).
  data.add<std::int32_t>(xml, in, "species", 1, n, [&](std::size_t i, std::size_t) { return g.species.type[i]; });
  data.add<double>(xml, in, "radius", 1, n, [&](std::size_t i, std::size_t) { return g.radius.r[i]; });
  // Diameter too, because ParaView's Glyph filter scales a unit sphere by diameter, not radius.
  data.add<double>(xml, in, "diameter", 1, n,
                   [&](std::size_t i, std::size_t) { return 2.0 * g.radius.r[i]; });
  if (fields.velocity) {
    const double* v[3] = {g.vel.x.data(), g.vel.y.data(), g.vel.z.data()};
    data.add<double>(xml, in, "velocity", 3, n, [&](std::size_t i, std::size_t c) { return v[c][i]; });
    data.add<double>(xml, in, "speed", 1, n, [&](std::size_t i, std::size_t) {
      return std::sqrt(v[0][i] * v[0][i] + v[1][i] * v[1][i] + v[2][i] * v[2][i]);
    });
  }
  if (fields.angular_velocity && g.spin) {  // grains that do not rotate have no spin to show
    const double* w[3] = {g.omega.x.data(), g.omega.y.data(), g.omega.z.data()};
    data.add<double>(xml, in, "angular_velocity", 3, n,
                     [&](std::size_t i, std::size_t c) { return w[c][i]; });
  }
  if (fields.force) {
    const double* f[3] = {g.force.x.data(), g.force.y.data(), g.force.z.data()};
    const double* fw[3] = {g.wall_force.x.data(), g.wall_force.y.data(), g.wall_force.z.data()};
    data.add<double>(xml, in, "force", 3, n,
                     [&](std::size_t i, std::size_t c) { return f[c][i] + fw[c][i]; });
  }
  for (const PointScalars& e : extra)
    data.add<double>(xml, in, e.name, 1, n, [&](std::size_t i, std::size_t) { return e.values[i]; });
  xml += "      </PointData>\n";

  xml += "      <Points>\n";
  {
    const double* p[3] = {g.pos.x.data(), g.pos.y.data(), g.pos.z.data()};
    data.add<double>(xml, in, "Points", 3, n, [&](std::size_t i, std::size_t c) { return p[c][i]; });
  }
  xml += "      </Points>\n";

  // One vertex cell per point: without cells ParaView loads the points but renders nothing
  // until a filter is applied.
  xml += "      <Verts>\n";
  data.add<std::int64_t>(xml, in, "connectivity", 1, n,
                         [](std::size_t i, std::size_t) { return static_cast<std::int64_t>(i); });
  data.add<std::int64_t>(xml, in, "offsets", 1, n,
                         [](std::size_t i, std::size_t) { return static_cast<std::int64_t>(i + 1); });
  xml += "      </Verts>\n";

  xml += "    </Piece>\n";
  xml += "  </PolyData>\n";
  xml += "  <AppendedData encoding=\"raw\">\n   _";
  xml += data.blob();
  xml += "\n  </AppendedData>\n";
  xml += "</VTKFile>\n";
  return xml;
}

FrameSeries::FrameSeries(std::filesystem::path out_dir, std::string name, std::string stem, bool one_file,
                         std::string extension)
    : dir_(std::move(out_dir)),
      name_(std::move(name)),
      stem_(std::move(stem)),
      extension_(std::move(extension)),
      one_file_(one_file) {
  ensure_directory(dir_ / name_);
}

std::filesystem::path FrameSeries::write(const Grains& g, double time, const FrameFields& fields,
                                         std::span<const PointScalars> extra) {
  return add(time, [&] { return vtp_bytes(g, fields, extra); });
}

std::filesystem::path FrameSeries::add(double time, const std::function<std::string()>& bytes) {
  // A NaN time would make the .pvd unreadable ("nan" is not a number to ParaView).
  if (!std::isfinite(time))
    throw std::invalid_argument("frame time must be finite, got " + shortest(time));

  const std::string rel = frame_name(frames_.size());
  const std::filesystem::path path = dir_ / rel;

  // Frame first, index second: the .pvd never names a frame that is not complete on disk.
  if (!one_file_ || frames_.empty() || !std::filesystem::exists(path)) write_file_atomic(path, bytes());
  frames_.push_back({time, rel});
  try {
    write_file_atomic(pvd_path(), pvd_bytes());
  } catch (...) {
    // Keep count() and the on-disk index in step, so a retry writes the same frame again.
    frames_.pop_back();
    throw;
  }
  return path;
}

std::string FrameSeries::frame_name(std::size_t index) const {
  // Six digits sort correctly in file browsers up to a million frames; past that the name
  // simply grows a digit and stays unique.
  char name[40];
  std::snprintf(name, sizeof name, "_%06zu", one_file_ ? std::size_t{0} : index);
  return name_ + "/" + stem_ + name + extension_;
}

std::vector<double> FrameSeries::times() const {
  std::vector<double> t;
  for (const Entry& e : frames_) t.push_back(e.time);
  return t;
}

void FrameSeries::resume(const std::vector<double>& times) {
  frames_.clear();
  for (double t : times) frames_.push_back({t, frame_name(frames_.size())});
  write_file_atomic(pvd_path(), pvd_bytes());
}

std::string FrameSeries::pvd_bytes() const {
  std::string s;
  s.reserve(160 + frames_.size() * 80);
  s += "<?xml version=\"1.0\"?>\n";
  s += "<VTKFile type=\"Collection\" version=\"1.0\" byte_order=\"";
  s += kByteOrder;
  s += "\" header_type=\"UInt64\">\n";
  s += "  <Collection>\n";
  for (const Entry& e : frames_) {
    s += "    <DataSet timestep=\"";
    s += shortest(e.time);
    s += "\" group=\"\" part=\"0\" file=\"";
    s += e.file;
    s += "\"/>\n";
  }
  s += "  </Collection>\n";
  s += "</VTKFile>\n";
  return s;
}

}  // namespace gf
