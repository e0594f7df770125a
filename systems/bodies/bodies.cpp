#include "systems/bodies/bodies.hpp"

#include "systems/bodies/member_core.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

namespace gf {

namespace {

template <class Table>
std::size_t table_bytes(Table& t) {
  std::size_t b = 0;
  std::apply([&b](auto&... comp) { (for_each_column(comp, [&b](auto& col) { b += col.bytes(); }), ...); },
             t.components());
  return b;
}

bool positive_finite(double v) { return std::isfinite(v) && v > 0.0; }

void check_body(const BodyRow& row) {
  if (!positive_finite(row.mass)) throw std::invalid_argument("a body's mass must be positive and finite");
  for (double i : row.inertia)
    if (!positive_finite(i)) throw std::invalid_argument("a body's principal moments must be positive and finite");
  const double qq = row.q[0] * row.q[0] + row.q[1] * row.q[1] + row.q[2] * row.q[2] + row.q[3] * row.q[3];
  if (!positive_finite(qq)) throw std::invalid_argument("a body's orientation quaternion must be nonzero and finite");
}

void check_member(const MemberRow& row) {
  if (row.vertices.empty()) throw std::invalid_argument("a member's core needs at least one vertex");
  for (const auto& v : row.vertices)
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw std::invalid_argument("a member's core vertex is not finite");
  if (row.kind != static_cast<std::uint8_t>(CoreKind::hull)) {
    std::vector<double> x, y, z;
    for (const auto& v : row.vertices) x.push_back(v[0]), y.push_back(v[1]), z.push_back(v[2]);
    check_core({static_cast<CoreKind>(row.kind), x, y, z});
  }
  if (!std::isfinite(row.radius) || row.radius < 0.0)
    throw std::invalid_argument("a member's dilation radius must be finite and not negative");
  if (row.vertices.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("a member's core has more vertices than a 32-bit count holds");
}

}  // namespace

void Bodies::resize(std::size_t rows) {
  std::apply([rows](auto&... comp) { (for_each_column(comp, [rows](auto& col) { col.resize(rows); }), ...); },
             components());
  n = rows;
}

std::size_t Bodies::push(const BodyRow& row) {
  check_body(row);
  const std::size_t i = n;
  resize(n + 1);
  pos.x[i] = row.x[0], pos.y[i] = row.x[1], pos.z[i] = row.x[2];
  const double norm = std::sqrt(row.q[0] * row.q[0] + row.q[1] * row.q[1] + row.q[2] * row.q[2] + row.q[3] * row.q[3]);
  q.w[i] = row.q[0] / norm, q.x[i] = row.q[1] / norm, q.y[i] = row.q[2] / norm, q.z[i] = row.q[3] / norm;
  vel.x[i] = row.v[0], vel.y[i] = row.v[1], vel.z[i] = row.v[2];
  omega.x[i] = row.w[0], omega.y[i] = row.w[1], omega.z[i] = row.w[2];
  mass.m[i] = row.mass, mass.inv_m[i] = 1.0 / row.mass;
  inertia.i1[i] = row.inertia[0], inertia.i2[i] = row.inertia[1], inertia.i3[i] = row.inertia[2];
  motion.state[i] = static_cast<std::uint8_t>(row.motion);
  if (row.motion != Motion::moving) {
    vel.x[i] = vel.y[i] = vel.z[i] = 0.0;
    omega.x[i] = omega.y[i] = omega.z[i] = 0.0;
  }
  return i;
}

std::size_t Bodies::bytes() { return table_bytes(*this); }

std::size_t Members::push(const MemberRow& row) {
  check_member(row);
  const std::size_t i = n, first = vertices.size(), count = row.vertices.size();
  if (first + count > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("the members' cores hold more vertices than a 32-bit index reaches");
  std::apply([&](auto&... comp) { (for_each_column(comp, [&](auto& col) { col.resize(i + 1); }), ...); },
             components());
  n = i + 1;
  double c[3] = {0, 0, 0};
  for (const auto& v : row.vertices)
    for (int k = 0; k < 3; ++k) c[k] += v[k] / static_cast<double>(count);
  double reach = 0.0;
  for (const auto& v : row.vertices) {
    vertices.x.push_back(v[0]), vertices.y.push_back(v[1]), vertices.z.push_back(v[2]);
    reach = std::max(reach, std::hypot(v[0] - c[0], v[1] - c[1], v[2] - c[2]));
  }
  if (row.kind != static_cast<std::uint8_t>(CoreKind::hull)) {  // another kind bounds itself
    const CoreView view{static_cast<CoreKind>(row.kind), std::span<const double>(vertices.x.data() + first, count),
                        std::span<const double>(vertices.y.data() + first, count),
                        std::span<const double>(vertices.z.data() + first, count)};
    const Eigen::Vector3d centre = core_centre(view);
    for (int k = 0; k < 3; ++k) c[k] = centre[k];
    reach = core_reach(view, centre);
  }
  body.row[i] = row.body;
  core.first[i] = static_cast<std::uint32_t>(first), core.count[i] = static_cast<std::uint32_t>(count);
  core.kind[i] = row.kind;
  dilation.r[i] = row.radius;
  bound.cx[i] = c[0], bound.cy[i] = c[1], bound.cz[i] = c[2];
  bound.radius[i] = reach + row.radius;
  return i;
}

std::size_t Members::bytes() {
  std::size_t b = table_bytes(*this);
  for_each_column(vertices, [&b](auto& col) { b += col.bytes(); });
  return b;
}

void remove_body(Bodies& b, std::size_t i) {
  if (i >= b.n) throw std::out_of_range("body row " + std::to_string(i) + " past the last of " + std::to_string(b.n));
  b.motion.state[i] = static_cast<std::uint8_t>(Motion::removed);
  for (ColumnD* c : {&b.vel.x, &b.vel.y, &b.vel.z, &b.omega.x, &b.omega.y, &b.omega.z, &b.force.x, &b.force.y,
                     &b.force.z, &b.torque.x, &b.torque.y, &b.torque.z})
    (*c)[i] = 0.0;
}

void place_members(Bodies& bodies, Members& members) {
  auto place = [&](std::size_t m) {
    const std::uint32_t b = members.body.row[m];
    if (b >= bodies.n) throw std::out_of_range("member " + std::to_string(m) + " names body row " + std::to_string(b) +
                                               ", past the last of " + std::to_string(bodies.n) + " bodies");
    const Eigen::Quaterniond q(bodies.q.w[b], bodies.q.x[b], bodies.q.y[b], bodies.q.z[b]);
    const Eigen::Vector3d c = q * Eigen::Vector3d(members.bound.cx[m], members.bound.cy[m], members.bound.cz[m]);
    members.centre.x[m] = bodies.pos.x[b] + c.x();
    members.centre.y[m] = bodies.pos.y[b] + c.y();
    members.centre.z[m] = bodies.pos.z[b] + c.z();
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, members.n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t m = r.begin(); m != r.end(); ++m) place(m);
  });
}

void PlaceMembers::run(World& world, const StepContext&) {
  place_members(world.tables.get<Bodies>(), world.tables.get<Members>());
}

}  // namespace gf
