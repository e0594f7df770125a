#include "systems/setup/repose_scene.hpp"

#include <cmath>
#include <string>

#include "systems/setup/body_fields.hpp"

namespace gf {

namespace {

V3<double> vec(const std::array<double, 3>& a) { return {a[0], a[1], a[2]}; }

const Field& repose_field(std::string_view key) { return kReposeFields.field(key); }

void refuse(const SceneNode& t, const char* key, const std::string& geometry) {
  if (t.has(repose_field(key).key))
    t.fail(key, std::string("a ") + geometry + " has no " + key,
           geometry == "heap" ? "give its axis as centre = [x, y, z]" : "give the direction across it as across = [x, y, z]");
}

// The optional box of members a heap is read from: { lo, hi }.
void read_heap_region(const SceneNode& t, ReposeSpec& s) {
  if (const auto region = t.maybe_table("region")) {
    s.has_region = true;
    const Field &lo = kReposeRegionFields.field("lo"), &hi = kReposeRegionFields.field("hi");
    s.lo = region->get_vec3(lo.key);
    s.hi = region->get_vec3(hi.key);
    for (std::size_t d = 0; d < 3; ++d)
      if (!(s.hi[d] > s.lo[d])) region->fail(hi.key, "it is not above lo on every axis", "give hi > lo component by component");
  }
}

ReposeSpec read_one(const SceneNode& t, const V3<double>& up) {
  ReposeSpec s;
  s.name = t.get_string(repose_field("name").key);
  const std::string g = read_choice(t, repose_field("geometry"), {"heap", "ridge", "crater"});
  s.geometry = g == "heap" ? ReposeSpec::Geometry::heap
                           : g == "ridge" ? ReposeSpec::Geometry::ridge : ReposeSpec::Geometry::crater;
  const Field& across = repose_field("across");
  if (s.geometry == ReposeSpec::Geometry::heap) {
    refuse(t, "across", g);
    s.centre = vec(t.get_vec3(repose_field("centre").key));
  } else {
    refuse(t, "centre", g);
    s.across = vec(t.get_vec3(across.key));
    const V3<double> flat = s.across - dot(s.across, up) * up;
    if (!(std::sqrt(dot(flat, flat)) > 1e-9 * std::sqrt(dot(s.across, s.across))))
      t.fail(across.key, "it is vertical (along gravity), so it crosses no slope", "give a horizontal direction");
  }
  s.settings.column = read_number(t, repose_field("column"));
  s.settings.rank = static_cast<int>(read_integer(t, repose_field("rank")));
  s.settings.lower = read_number(t, repose_field("lower"));
  const Field& upper = repose_field("upper");
  s.settings.upper = read_number(t, upper);
  if (!(s.settings.lower < s.settings.upper))
    t.fail(upper.key, "it is not above lower", "fit a part of the flank: 0 <= lower < upper <= 1");
  read_heap_region(t, s);
  return s;
}

}  // namespace

std::vector<ReposeSpec> read_repose(const SceneNode& analysis, const V3<double>& up) {
  std::vector<ReposeSpec> out;
  for (const SceneNode& t : analysis.tables("repose")) {
    out.push_back(read_one(t, up));
    for (std::size_t k = 0; k + 1 < out.size(); ++k)
      if (out[k].name == out.back().name)
        t.fail(repose_field("name").key, "another [[analysis.repose]] has the name '" + out.back().name + "'",
               "give each a name of its own");
  }
  return out;
}

}  // namespace gf
