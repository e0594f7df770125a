#include "systems/setup/dem_body_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/contact/laws.hpp"

namespace gf {

namespace {

std::string col(std::size_t k) { return "bodies.column." + std::to_string(k); }

template <class F>
void for_each_body_column(Bodies& b, F f) {
  std::apply([&](auto&... comp) { (for_each_column(comp, f), ...); }, b.components());
}

// The contact state's arrays, under fixed names, for both directions.
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

void require(const CheckpointReader& in, bool ok, const std::string& what) {
  if (!ok) in.fail("it is inconsistent (" + what + ")", "resume from an earlier checkpoint, or run the scene again");
}

template <class T>
void require_equal(const CheckpointReader& in, const char* what, T stored, T now, const std::string& fix) {
  if (stored != now)
    in.fail(std::string("it was written with ") + what + " = " + std::to_string(stored) + ", the scene now gives " +
                std::to_string(now),
            fix);
}

template <class T>
bool all_below(const std::vector<T>& v, std::size_t n) {
  return std::all_of(v.begin(), v.end(), [n](T x) { return static_cast<std::size_t>(x) < n; });
}

}  // namespace

void save_body_state(CheckpointWriter& out, World& world, const DemScene& scene) {
  Bodies& b = world.tables.get<Bodies>();
  Members& m = world.tables.get<Members>();
  BodyContactState& s = world.resources.get<BodyContactState>();
  out.value("clock.t", world.clock.t);
  out.value("clock.dt", world.clock.dt);
  out.value("clock.step", world.clock.step);
  out.value("clock.t0", world.clock.t0);
  out.vector("contact.law", std::vector<char>(scene.law.begin(), scene.law.end()));
  out.value("scene.walls", static_cast<std::uint64_t>(scene.walls.size()));
  out.value("scene.shapes", static_cast<std::uint64_t>(scene.bodies->shapes.size()));
  out.value("bodies.n", static_cast<std::uint64_t>(b.n));
  out.value("members.n", static_cast<std::uint64_t>(m.n));
  std::size_t k = 0;
  for_each_body_column(b, [&](auto& c) { out.column(col(k++), c); });
  out.column("members.centre.x", m.centre.x);
  out.column("members.centre.y", m.centre.y);
  out.column("members.centre.z", m.centre.z);
  out.value("body_contact.skin", s.skin);
  out.value("body_contact.valid", s.valid);
  out.value("body_contact.rebuilds", s.rebuilds);
  out.value("body_contact.list.width", static_cast<std::uint64_t>(s.list.width));
  out.value("body_contact.walls.members", static_cast<std::uint64_t>(s.walls.members));
  out.value("body_contact.walls.planes", static_cast<std::uint64_t>(s.walls.planes));
  out.value("body_contact.walls.width", static_cast<std::uint64_t>(s.walls.width));
  out.value("body_contact.last", s.last);
  contact_sections(out, s);
}

void restore_body_state(const CheckpointReader& in, World& world, const DemScene& scene) {
  const std::string same_scene = "resume with the scene (and --set overrides) of the run that wrote the checkpoint";
  if (!in.has("bodies.n"))
    in.fail("it holds no composite bodies (a run of grains wrote it)", same_scene);
  require_equal<double>(in, "run.dt", in.value<double>("clock.dt"), scene.dt,
                        "resume with the same run.dt: a checkpoint continues a run, it does not change its step");
  std::vector<char> law;
  in.vector("contact.law", law);
  if (std::string(law.begin(), law.end()) != scene.law)
    in.fail("it was written with the contact law '" + std::string(law.begin(), law.end()) + "', the scene now uses '" +
                scene.law + "'",
            "resume with the scene's original [contact] model: a checkpoint carries that law's springs");
  Bodies& b = world.tables.get<Bodies>();
  Members& m = world.tables.get<Members>();
  BodyContactState& s = world.resources.get<BodyContactState>();
  require_equal<std::uint64_t>(in, "wall count", in.value<std::uint64_t>("scene.walls"), scene.walls.size(), same_scene);
  require_equal<std::uint64_t>(in, "shape count", in.value<std::uint64_t>("scene.shapes"), scene.bodies->shapes.size(),
                               same_scene);
  require_equal<std::uint64_t>(in, "body count", in.value<std::uint64_t>("bodies.n"), b.n, same_scene);
  require_equal<std::uint64_t>(in, "member count", in.value<std::uint64_t>("members.n"), m.n, same_scene);
  require_equal<double>(in, "run.skin", in.value<double>("body_contact.skin"), s.skin, "resume with the same run.skin");

  world.clock.t = in.value<double>("clock.t");
  world.clock.dt = in.value<double>("clock.dt");
  world.clock.step = in.value<std::int64_t>("clock.step");
  world.clock.t0 = in.value<double>("clock.t0");
  std::size_t k = 0;
  for_each_body_column(b, [&](auto& c) {
    const std::size_t rows = c.size();
    in.column(col(k++), c);
    if (c.size() != rows) in.fail("a body column has the wrong length", same_scene);
  });
  for (ColumnD* c : {&m.centre.x, &m.centre.y, &m.centre.z}) {
    const std::size_t rows = c->size();
    in.column(c == &m.centre.x ? "members.centre.x" : c == &m.centre.y ? "members.centre.y" : "members.centre.z", *c);
    if (c->size() != rows) in.fail("a member column has the wrong length", same_scene);
  }
  s.valid = in.value<bool>("body_contact.valid");
  s.rebuilds = in.value<std::int64_t>("body_contact.rebuilds");
  s.list.width = in.value<std::uint64_t>("body_contact.list.width");
  s.walls.members = in.value<std::uint64_t>("body_contact.walls.members");
  s.walls.planes = in.value<std::uint64_t>("body_contact.walls.planes");
  s.walls.width = in.value<std::uint64_t>("body_contact.walls.width");
  s.last = in.value<BodyContactReport>("body_contact.last");
  // The springs' layout is the law's (adopt_layout in the contacts); set it before reading them by name.
  with_law(scene.law, [&]<class L>() { set_layout(s.history, L::history()); });
  contact_sections(in, s);

  // Every value used as an index or a count, checked.
  for (std::size_t i = 0; i < b.n; ++i)
    require(in, b.motion.state[i] <= static_cast<std::uint8_t>(Motion::removed) && b.mass.m[i] > 0 &&
                    std::isfinite(b.pos.x[i] + b.pos.y[i] + b.pos.z[i]),
            "a body's motion, mass or position");
  const std::size_t pairs = s.list.key.size();
  require(in, s.list.a.size() == pairs && s.list.b.size() == pairs && all_below(s.list.a, m.n) &&
                  all_below(s.list.b, m.n) && std::is_sorted(s.list.key.begin(), s.list.key.end()),
          "member-pair list");
  require(in, s.list.constants.size() == pairs * s.list.width || s.list.constants.empty(), "member-pair constants");
  require(in, s.list.wall_constants.size() == m.n * s.list.width || s.list.wall_constants.empty(), "wall constants");
  require(in, std::all_of(s.history.pair.begin(), s.history.pair.end(),
                          [&](std::int32_t p) { return p >= 0 && static_cast<std::size_t>(p) < pairs; }),
          "member-pair springs");
  require(in, std::all_of(s.history.slot.begin(), s.history.slot.end(),
                          [&](std::int32_t e) { return e >= -1 && e < static_cast<std::int64_t>(s.history.size()); }),
          "member-pair spring slots");
  require(in, s.walls.value.size() == s.walls.members * s.walls.planes * s.walls.width &&
                  s.walls.touching.size() == s.walls.members * s.walls.planes,
          "member-wall springs");
  require(in, (s.ref_x.empty() || s.ref_x.size() == m.n) && s.ref_y.size() == s.ref_x.size() &&
                  s.ref_z.size() == s.ref_x.size() && (s.motion.empty() || s.motion.size() == m.n),
          "member reference centres");
}

}  // namespace gf
