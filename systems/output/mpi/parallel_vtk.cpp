#include "systems/output/mpi/parallel_vtk.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <stdexcept>

namespace gf {

namespace {

constexpr const char* kByteOrder = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

std::string header(const char* type) {
  return std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"") + type + "\" version=\"1.0\" byte_order=\"" +
         kByteOrder + "\" header_type=\"UInt64\">\n";
}

// The text of `xml` between `open` (from its start) and `close`; empty if either is missing.
std::string_view section(std::string_view xml, std::string_view open, std::string_view close) {
  const std::size_t a = xml.find(open);
  if (a == std::string_view::npos) return {};
  const std::size_t b = xml.find(close, a);
  return b == std::string_view::npos ? std::string_view{} : xml.substr(a, b - a);
}

// Each `<DataArray type=... Name=... NumberOfComponents=...` of `part` as a PDataArray line
// (the attributes up to format=, which places the data in the piece).
std::string declarations(std::string_view part, std::string_view indent) {
  std::string out;
  for (std::size_t at = part.find("<DataArray "); at != std::string_view::npos;
       at = part.find("<DataArray ", at + 1)) {
    const std::size_t end = part.find(" format=", at);
    if (end == std::string_view::npos) throw std::invalid_argument("a VTK piece's DataArray has no format");
    const std::string_view attrs = part.substr(at + 11, end - at - 11);
    out += std::string(indent) + "<PDataArray " + std::string(attrs) + "/>\n";
  }
  return out;
}

// The attributes of the piece's <PointData ...> tag (Scalars=, Vectors=), with their leading space.
std::string_view point_data_attributes(std::string_view xml) {
  const std::string_view tag = section(xml, "<PointData", ">");
  return tag.substr(std::min<std::size_t>(tag.size(), 10));
}

std::string shortest(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

}  // namespace

std::string pvtp_bytes(std::string_view piece, std::span<const std::string> sources) {
  const std::string_view head = piece.substr(0, piece.find("<AppendedData"));
  const std::string_view points = section(head, "<Points>", "</Points>");
  if (points.find("<DataArray ") == std::string_view::npos)
    throw std::invalid_argument("a VTK piece without a Points array cannot be indexed in a .pvtp");
  std::string s = header("PPolyData");
  s += "  <PPolyData GhostLevel=\"0\">\n";
  s += "    <PPointData" + std::string(point_data_attributes(head)) + ">\n";
  s += declarations(section(head, "<PointData", "</PointData>"), "      ");
  s += "    </PPointData>\n    <PPoints>\n";
  s += declarations(points, "      ");
  s += "    </PPoints>\n";
  for (const std::string& src : sources) s += "    <Piece Source=\"" + src + "\"/>\n";
  s += "  </PPolyData>\n</VTKFile>\n";
  return s;
}

std::string pvd_bytes(std::span<const PvdEntry> entries) {
  std::string s = header("Collection");
  s += "  <Collection>\n";
  for (const PvdEntry& e : entries)
    s += "    <DataSet timestep=\"" + shortest(e.time) + "\" group=\"\" part=\"0\" file=\"" + e.file + "\"/>\n";
  s += "  </Collection>\n</VTKFile>\n";
  return s;
}

}  // namespace gf
