#include "systems/setup/repose_scene.hpp"

#include <cmath>
#include <string>

namespace gf {

namespace {

V3<double> vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

void refuse(const SceneNode& t, const char* key, const std::string& geometry) {
  if (t.has(key))
    t.fail(key, std::string("a ") + geometry + " has no " + key,
           geometry == "heap" ? "give its axis as centre = [x, y, z]" : "give the direction across it as across = [x, y, z]");
}

ReposeSpec read_one(const SceneNode& t, const V3<double>& up) {
  ReposeSpec s;
  s.name = t.get_string("name");
  const std::string g = t.get_choice("geometry", {"heap", "ridge", "crater"});
  s.geometry = g == "heap" ? ReposeSpec::Geometry::heap
                           : g == "ridge" ? ReposeSpec::Geometry::ridge : ReposeSpec::Geometry::crater;
  if (s.geometry == ReposeSpec::Geometry::heap) {
    refuse(t, "across", g);
    s.centre = vec(t.get_vec3("centre"));
  } else {
    refuse(t, "centre", g);
    s.across = vec(t.get_vec3("across"));
    const V3<double> flat = s.across - dot(s.across, up) * up;
    if (!(std::sqrt(dot(flat, flat)) > 1e-9 * std::sqrt(dot(s.across, s.across))))
      t.fail("across", "it is vertical (along gravity), so it crosses no slope", "give a horizontal direction");
  }
  s.settings.column = t.get_double("column", Range::positive());
  s.settings.rank = static_cast<int>(t.get_int("rank", 3, 1, 1000));
  s.settings.lower = t.get_double("lower", 0.15, Range::closed(0.0, 1.0));
  s.settings.upper = t.get_double("upper", 0.85, Range::closed(0.0, 1.0));
  if (!(s.settings.lower < s.settings.upper))
    t.fail("upper", "it is not above lower", "fit a part of the flank: 0 <= lower < upper <= 1");
  if (const auto region = t.maybe_table("region")) {
    s.has_region = true;
    s.lo = region->get_vec3("lo");
    s.hi = region->get_vec3("hi");
    for (std::size_t d = 0; d < 3; ++d)
      if (!(s.hi[d] > s.lo[d])) region->fail("hi", "it is not above lo on every axis", "give hi > lo component by component");
  }
  return s;
}

}  // namespace

std::vector<ReposeSpec> read_repose(const SceneNode& analysis, const V3<double>& up) {
  std::vector<ReposeSpec> out;
  for (const SceneNode& t : analysis.tables("repose")) {
    out.push_back(read_one(t, up));
    for (std::size_t k = 0; k + 1 < out.size(); ++k)
      if (out[k].name == out.back().name)
        t.fail("name", "another [[analysis.repose]] has the name '" + out.back().name + "'", "give each a name of its own");
  }
  return out;
}

}  // namespace gf
