#include "systems/analysis/body_repose.hpp"

#include <algorithm>
#include <limits>

#include "systems/bodies/member_geometry.hpp"

namespace gf {

namespace {

bool inside(const ReposeSpec& s, const Eigen::Vector3d& c) {
  if (!s.has_region) return true;
  for (int d = 0; d < 3; ++d)
    if (c[d] < s.lo[static_cast<std::size_t>(d)] || c[d] > s.hi[static_cast<std::size_t>(d)]) return false;
  return true;
}

}  // namespace

MemberTops member_tops(const Bodies& bodies, const Members& members, const V3<double>& up, const ReposeSpec& spec) {
  const Eigen::Vector3d u(up.x, up.y, up.z);
  MemberTops t;
  for (std::size_t m = 0; m < members.n; ++m) {
    if (!bodies.moving(members.body.row[m])) continue;
    const MemberShape shape = member_shape(bodies, members, m);
    if (!inside(spec, shape.bound_centre)) continue;
    const double top = u.dot(shape.support(u));
    t.x.push_back(shape.bound_centre.x());
    t.y.push_back(shape.bound_centre.y());
    t.z.push_back(shape.bound_centre.z());
    t.r.push_back(top + shape.radius - u.dot(shape.bound_centre));
  }
  return t;
}

Repose body_repose(const Bodies& bodies, const Members& members, const V3<double>& up, const ReposeSpec& spec) {
  const MemberTops t = member_tops(bodies, members, up, spec);
  if (spec.geometry == ReposeSpec::Geometry::heap) return repose_radial(t.view(), spec.centre, up, spec.settings);
  return repose_planar(t.view(), spec.across, up, spec.settings, spec.geometry == ReposeSpec::Geometry::crater);
}

}  // namespace gf
