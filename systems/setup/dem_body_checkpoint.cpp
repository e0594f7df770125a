#include "systems/setup/dem_body_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>

#include "systems/bodies/bodies.hpp"
#include "engine/clock_checkpoint.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/bodies/body_contact_checkpoint.hpp"
#include "systems/contact/laws.hpp"

namespace gf {

namespace {

std::string col(std::size_t k) { return "bodies.column." + std::to_string(k); }

template <class F>
void for_each_body_column(Bodies& b, F f) {
  std::apply([&](auto&... comp) { (for_each_column(comp, f), ...); }, b.components());
}

}  // namespace

void save_body_state(CheckpointWriter& out, World& world, const DemScene& scene) {
  Bodies& b = world.tables.get<Bodies>();
  Members& m = world.tables.get<Members>();
  BodyContactState& s = world.resources.get<BodyContactState>();
  save_clock(out, world.clock);
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
  save_body_contact(out, s);
}

void restore_body_state(const CheckpointReader& in, World& world, const DemScene& scene) {
  const std::string same_scene = "resume with the scene (and --set overrides) of the run that wrote the checkpoint";
  if (!in.has("bodies.n"))
    in.fail("it holds no composite bodies (a run of grains wrote it)", same_scene);
  in.require_equal<double>("run.dt", in.value<double>("clock.dt"), scene.dt,
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
  in.require_equal<std::uint64_t>("wall count", in.value<std::uint64_t>("scene.walls"), scene.walls.size(), same_scene);
  in.require_equal<std::uint64_t>("shape count", in.value<std::uint64_t>("scene.shapes"), scene.bodies->shapes.size(),
                                  same_scene);
  in.require_equal<std::uint64_t>("body count", in.value<std::uint64_t>("bodies.n"), b.n, same_scene);
  in.require_equal<std::uint64_t>("member count", in.value<std::uint64_t>("members.n"), m.n, same_scene);
  in.require_equal<double>("run.skin", in.value<double>("body_contact.skin"), s.skin, "resume with the same run.skin");

  restore_clock(in, world.clock);
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
  // The springs' layout is the law's (adopt_layout in the contacts); set it before reading them by name.
  with_law(scene.law, [&]<class L>() { set_layout(s.history, L::history()); });
  restore_body_contact(in, s, m.n);
  // Every value used as an index or a count, checked.
  for (std::size_t i = 0; i < b.n; ++i)
    in.require(b.motion.state[i] <= static_cast<std::uint8_t>(Motion::removed) && b.mass.m[i] > 0 &&
                   std::isfinite(b.pos.x[i] + b.pos.y[i] + b.pos.z[i]),
               "a body's motion, mass or position", kFixResumeOrRerun);
}

}  // namespace gf
