#include "systems/bodies/member_core.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

#include "systems/bodies/mass_properties.hpp"

namespace gf {

using Eigen::Vector3d;

namespace {

// ---- The hull of a list of points ----------------------------------------------------------------

// The point farthest along d; the first of ties.
Vector3d hull_support(const CoreView& c, const Vector3d& d) {
  std::size_t best = 0;
  double top = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double h = d.x() * c.x[i] + d.y() * c.y[i] + d.z() * c.z[i];
    if (h > top) top = h, best = i;
  }
  return c.point(best);
}

// The mean of the points: cheap and exact to recompute.
Vector3d hull_centre(const CoreView& c) {
  Vector3d sum = Vector3d::Zero();
  for (std::size_t i = 0; i < c.size(); ++i) sum += c.point(i);
  return sum / static_cast<double>(c.size());
}

double hull_reach(const CoreView& c, const Vector3d& centre) {
  double reach = 0;
  for (std::size_t i = 0; i < c.size(); ++i) reach = std::max(reach, (c.point(i) - centre).norm());
  return reach;
}

class HullSolid final : public CoreSolid {
 public:
  explicit HullSolid(std::vector<Vector3d> points) : core_(std::move(points)) {}
  double distance(const Vector3d& p) const override { return core_.distance(p); }
  bool dilated_contains(const Vector3d& p, double r) const override { return core_.dilated_contains(p, r); }

 private:
  ConvexCore core_;
};

std::vector<Vector3d> hull_outline(const CoreView& c) {
  std::vector<Vector3d> out;
  for (std::size_t i = 0; i < c.size(); ++i) out.push_back(c.point(i));
  return out;
}

std::unique_ptr<CoreSolid> hull_solid(const CoreView& c) { return std::make_unique<HullSolid>(hull_outline(c)); }

void hull_check(const CoreView& c) {
  for (std::size_t i = 0; i < c.size(); ++i)
    if (!c.point(i).allFinite()) throw std::invalid_argument("a vertex is not finite");
}

// ---- The table: one row per kind -----------------------------------------------------------------

const CoreModel kModels[] = {
    {"hull", 1, kMaxCoreVertices, true, hull_support, hull_centre, hull_reach, hull_solid, hull_outline, hull_check},
    {"ellipsoid", 4, 4, false, ellipsoid_core::support, ellipsoid_core::centre, ellipsoid_core::reach,
     ellipsoid_core::solid, ellipsoid_core::outline, ellipsoid_core::check},
};

}  // namespace

const CoreModel& core_model(CoreKind kind) {
  const auto k = static_cast<std::size_t>(kind);
  if (k >= std::size(kModels)) throw std::invalid_argument("no member core of kind " + std::to_string(k));
  return kModels[k];
}

void check_core(const CoreView& c) {
  const CoreModel& m = core_model(c.kind);
  const std::string kind(m.name);
  if (c.y.size() != c.size() || c.z.size() != c.size())
    throw std::invalid_argument("a member's " + kind + " core needs x, y and z of one length");
  if (c.size() < m.min_points || c.size() > m.max_points)
    throw std::invalid_argument("a member's " + kind + " core has " + std::to_string(c.size()) + " points, not " +
                                (m.min_points == m.max_points ? std::to_string(m.min_points)
                                                              : std::to_string(m.min_points) + " to " +
                                                                    std::to_string(m.max_points)));
  try {
    m.check(c);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("a member's " + kind + " core: " + e.what());
  }
}

CorePoints::CorePoints(std::span<const Vector3d> points, CoreKind k) : kind(k) {
  for (const Vector3d& p : points) x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
}

}  // namespace gf
