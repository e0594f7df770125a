#include "systems/output/body_vtu.hpp"

#include <Eigen/Geometry>

#include <cstdint>
#include <span>

#include "systems/bodies/member_core.hpp"
#include "systems/output/vtk_appended.hpp"

namespace gf {

namespace {

// VTK cell types.
constexpr std::uint8_t kVertex = 1, kLine = 3, kConvexPointSet = 41;

}  // namespace

std::string body_vtu_bytes(const Bodies& b, const Members& m, const std::vector<std::size_t>& shape,
                           const std::vector<int>& group) {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::int64_t> offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::size_t> member;  // per cell
  for (std::size_t k = 0; k < m.n; ++k) {
    const std::uint32_t body = m.body.row[k];
    if (b.motion.state[body] == static_cast<std::uint8_t>(Motion::removed)) continue;
    const Eigen::Quaterniond q(b.q.w[body], b.q.x[body], b.q.y[body], b.q.z[body]);
    const Eigen::Vector3d x(b.pos.x[body], b.pos.y[body], b.pos.z[body]);
    const std::uint32_t first = m.core.first[k], count = m.core.count[k];
    const std::size_t before = points.size();
    if (m.core.kind[k] == static_cast<std::uint8_t>(CoreKind::hull)) {
      for (std::uint32_t v = first; v < first + count; ++v)
        points.push_back(x + q * Eigen::Vector3d(m.vertices.x[v], m.vertices.y[v], m.vertices.z[v]));
    } else {
      const CoreView core{static_cast<CoreKind>(m.core.kind[k]),
                          std::span<const double>(m.vertices.x.data() + first, count),
                          std::span<const double>(m.vertices.y.data() + first, count),
                          std::span<const double>(m.vertices.z.data() + first, count)};
      for (const Eigen::Vector3d& v : core_outline(core)) points.push_back(x + q * v);
    }
    const std::size_t n = points.size() - before;
    offsets.push_back(static_cast<std::int64_t>(points.size()));
    types.push_back(n == 1 ? kVertex : (n == 2 ? kLine : kConvexPointSet));
    member.push_back(k);
  }
  const std::size_t np = points.size(), nc = member.size();
  vtk::AppendedArrays data;
  std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"";
  xml += vtk::kByteOrder;
  xml += "\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  xml += "    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" NumberOfCells=\"" + std::to_string(nc) + "\">\n";
  const std::string_view in = "        ";
  const auto body_of = [&](std::size_t c) { return m.body.row[member[c]]; };
  xml += "      <CellData Scalars=\"shape\">\n";
  data.add<std::int64_t>(xml, in, "body", 1, nc, [&](std::size_t c, std::size_t) { return static_cast<std::int64_t>(body_of(c)); });
  data.add<std::int32_t>(xml, in, "shape", 1, nc,
                         [&](std::size_t c, std::size_t) { return static_cast<std::int32_t>(shape[body_of(c)]); });
  data.add<std::int32_t>(xml, in, "group", 1, nc, [&](std::size_t c, std::size_t) { return group[body_of(c)]; });
  data.add<std::int32_t>(xml, in, "motion", 1, nc,
                         [&](std::size_t c, std::size_t) { return static_cast<std::int32_t>(b.motion.state[body_of(c)]); });
  data.add<double>(xml, in, "radius", 1, nc, [&](std::size_t c, std::size_t) { return m.dilation.r[member[c]]; });
  xml += "      </CellData>\n      <Points>\n";
  data.add<double>(xml, in, "Points", 3, np, [&](std::size_t i, std::size_t c) { return points[i][static_cast<int>(c)]; });
  xml += "      </Points>\n      <Cells>\n";
  data.add<std::int64_t>(xml, in, "connectivity", 1, np, [](std::size_t i, std::size_t) { return static_cast<std::int64_t>(i); });
  data.add<std::int64_t>(xml, in, "offsets", 1, nc, [&](std::size_t c, std::size_t) { return offsets[c]; });
  data.add<std::uint8_t>(xml, in, "types", 1, nc, [&](std::size_t c, std::size_t) { return types[c]; });
  xml += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  xml += data.blob();
  xml += "\n  </AppendedData>\n</VTKFile>\n";
  return xml;
}

}  // namespace gf
