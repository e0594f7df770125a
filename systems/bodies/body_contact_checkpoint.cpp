#include "systems/bodies/body_contact_checkpoint.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace gf {

namespace {

// The state's arrays, under fixed names, for both directions.
template <class Io, class State>
void contact_sections(Io& io, State& s) {
  io.vector("body_contact.ref_x", s.ref_x);
  io.vector("body_contact.ref_y", s.ref_y);
  io.vector("body_contact.ref_z", s.ref_z);
  io.vector("body_contact.list.a", s.list.a);
  io.vector("body_contact.list.b", s.list.b);
  io.vector("body_contact.list.key", s.list.key);
  io.vector("body_contact.list.constants", s.list.constants);
  io.vector("body_contact.list.wall_constants", s.list.wall_constants);
  const std::string c = "body_contact.history." + s.history.component;
  io.column(c + ".pair", s.history.pair);
  for (std::size_t q = 0; q < s.history.width; ++q) io.column(c + "." + s.history.fields[q], s.history.value[q]);
  io.column(c + ".slot", s.history.slot);
  io.vector("body_contact.walls.value", s.walls.value);
  io.vector("body_contact.walls.touching", s.walls.touching);
  io.vector("body_contact.motion", s.motion);
}

template <class T>
bool all_below(const std::vector<T>& v, std::size_t n) {
  return std::all_of(v.begin(), v.end(), [n](T x) { return static_cast<std::size_t>(x) < n; });
}

void check_body_contact(const CheckpointReader& in, const BodyContactState& s, std::size_t members) {
  const std::size_t pairs = s.list.key.size();
  in.require(s.list.a.size() == pairs && s.list.b.size() == pairs && all_below(s.list.a, members) &&
                 all_below(s.list.b, members) && std::is_sorted(s.list.key.begin(), s.list.key.end()),
             "member-pair list", kFixResumeOrRerun);
  in.require(s.list.constants.size() == pairs * s.list.width || s.list.constants.empty(), "member-pair constants", kFixResumeOrRerun);
  in.require(s.list.wall_constants.size() == members * s.list.width || s.list.wall_constants.empty(),
             "wall constants", kFixResumeOrRerun);
  in.require(std::all_of(s.history.pair.begin(), s.history.pair.end(),
                         [&](std::int32_t p) { return p >= 0 && static_cast<std::size_t>(p) < pairs; }),
             "member-pair springs", kFixResumeOrRerun);
  in.require(std::all_of(s.history.slot.begin(), s.history.slot.end(),
                         [&](std::int32_t e) { return e >= -1 && e < static_cast<std::int64_t>(s.history.size()); }),
             "member-pair spring slots", kFixResumeOrRerun);
  in.require(s.walls.value.size() == s.walls.members * s.walls.planes * s.walls.width &&
                 s.walls.touching.size() == s.walls.members * s.walls.planes,
             "member-wall springs", kFixResumeOrRerun);
  in.require((s.ref_x.empty() || s.ref_x.size() == members) && s.ref_y.size() == s.ref_x.size() &&
                 s.ref_z.size() == s.ref_x.size() && (s.motion.empty() || s.motion.size() == members),
             "member reference centres", kFixResumeOrRerun);
}

}  // namespace

void save_body_contact(CheckpointWriter& out, const BodyContactState& s) {
  out.value("body_contact.skin", s.skin);
  out.value("body_contact.valid", s.valid);
  out.value("body_contact.rebuilds", s.rebuilds);
  out.value("body_contact.list.width", static_cast<std::uint64_t>(s.list.width));
  out.value("body_contact.walls.members", static_cast<std::uint64_t>(s.walls.members));
  out.value("body_contact.walls.planes", static_cast<std::uint64_t>(s.walls.planes));
  out.value("body_contact.walls.width", static_cast<std::uint64_t>(s.walls.width));
  out.value("body_contact.last", s.last);
  contact_sections(out, s);
  save_wall_loads(out, "body_contact.loads", s.loads);
}

void restore_body_contact(const CheckpointReader& in, BodyContactState& s, std::size_t members) {
  s.valid = in.value<bool>("body_contact.valid");
  s.rebuilds = in.value<std::int64_t>("body_contact.rebuilds");
  s.list.width = in.value<std::uint64_t>("body_contact.list.width");
  s.walls.members = in.value<std::uint64_t>("body_contact.walls.members");
  s.walls.planes = in.value<std::uint64_t>("body_contact.walls.planes");
  s.walls.width = in.value<std::uint64_t>("body_contact.walls.width");
  s.last = in.value<BodyContactReport>("body_contact.last");
  contact_sections(in, s);
  restore_wall_loads(in, "body_contact.loads", s.loads);
  check_body_contact(in, s, members);
}

}  // namespace gf
