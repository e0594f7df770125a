#include "systems/setup/dem_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "engine/clock_checkpoint.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/broadphase/broadphase_checkpoint.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/periodic/periodic_checkpoint.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/broadphase/list_sections.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

namespace {

std::string g(std::size_t k) { return "grains.column." + std::to_string(k); }
std::string x(std::size_t k) { return "grains.attached." + std::to_string(k); }

void check_grains(const CheckpointReader& in, const Grains& g, std::size_t species, const Walls& walls) {
  for (std::size_t i = 0; i < g.n; ++i) {
    // As for a state file's grain: a centre behind a wall is outside the domain.
    for (const Wall& w : walls.list) {
      Vec3d n;
      in.require(!(wall_gap(w, {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, n) <= 0.0),
                 "a grain's centre is outside wall '" + w.name + "'", kFixResumeOrStateFile);
    }
    in.require(g.species.type[i] >= 0 && static_cast<std::size_t>(g.species.type[i]) < species,
               "a grain's species is out of range", kFixResumeOrStateFile);
    in.require(std::isfinite(g.pos.x[i]) && std::isfinite(g.pos.y[i]) && std::isfinite(g.pos.z[i]),
               "a grain's position is not finite", kFixResumeOrStateFile);
    in.require(g.radius.r[i] > 0 && std::isfinite(g.radius.r[i]) && g.mass.m[i] > 0 && std::isfinite(g.mass.m[i]),
               "a grain's radius or mass is not a positive number", kFixResumeOrStateFile);
  }
  for (const GrainRow& r : g.pending.insert)
    in.require(r.type >= 0 && static_cast<std::size_t>(r.type) < species, "a queued grain's species is out of range", kFixResumeOrStateFile);
}

}  // namespace

void save_dem_state(CheckpointWriter& out, World& world, const DemScene& scene) {
  save_clock(out, world.clock);
  save_dem_rows(out, world, scene);
}

void restore_dem_state(const CheckpointReader& in, World& world, const DemScene& scene) {
  in.require_equal<double>("run.dt", in.value<double>("clock.dt"), scene.dt,
                           "resume with the same run.dt: a checkpoint continues a run, it does not change its step");
  restore_clock(in, world.clock);
  restore_dem_rows(in, world, scene);
}

void save_dem_rows(CheckpointWriter& out, World& world, const DemScene& scene) {
  Grains& gr = world.grains;
  out.value("scene.species", static_cast<std::uint64_t>(scene.species.size()));
  out.value("scene.walls", static_cast<std::uint64_t>(scene.walls.size()));
  out.vector("contact.law", std::vector<char>(scene.law.begin(), scene.law.end()));
  out.value("grains.n_owned", static_cast<std::uint64_t>(gr.n_owned));
  out.value("grains.n", static_cast<std::uint64_t>(gr.n));
  out.value("grains.next_id", gr.next_id);
  out.value("grains.spin", gr.spin);
  out.vector("grains.pending.insert", gr.pending.insert);
  out.vector("grains.pending.remove", gr.pending.remove);
  std::size_t k = 0;
  gr.for_each_core_column([&](auto& col) { out.column(g(k++), col); });
  k = 0;
  for (const RawColumn& c : gr.extras.raw_columns()) out.raw(x(k++), c.data, c.elem_size, c.size);

  auto& bp = world.resources.get<BroadphaseState>();
  save_broadphase(out, bp, "");
  out.value("walls.rotation_enabled", world.resources.get<Walls>().rotation_enabled);
  save_wall_loads(out, "walls.loads", world.resources.get<Walls>().loads);
  if (const MeshWallLoads* m = world.resources.find<MeshWallLoads>()) save_wall_loads(out, "mesh_walls.loads", *m);
  list_sections(out, world.resources.get<NeighborList>(), world.resources.get<PairHistory>(), bp, "");
  save_periodic_images(out, world.resources.get<PeriodicImages>());
  if (const FlowState* f = world.resources.find<FlowState>()) save_flow_state(out, *f);
}

void restore_dem_rows(const CheckpointReader& in, World& world, const DemScene& scene) {
  const std::string same_scene = "resume with the scene (and --set overrides) of the run that wrote the checkpoint";
  in.require_equal<std::uint64_t>("species count", in.value<std::uint64_t>("scene.species"), scene.species.size(),
                                  same_scene);
  in.require_equal<std::uint64_t>("wall count", in.value<std::uint64_t>("scene.walls"), scene.walls.size(),
                                  same_scene);
  std::vector<char> law;
  if (in.has("contact.law")) in.vector("contact.law", law);
  const std::string stored_law(law.begin(), law.end());
  if (stored_law != scene.law)
    in.fail((stored_law.empty() ? std::string("it records no contact law (an earlier build wrote it)")
                                : "it was written with the contact law '" + stored_law + "'") +
                ", the scene now uses '" + scene.law + "'",
            "resume with the scene's original [contact] model: a checkpoint carries that law's history");
  Grains& gr = world.grains;
  if (in.has("grains.spin") && in.value<bool>("grains.spin") != gr.spin)
    in.fail(std::string("it was written for grains that ") + (gr.spin ? "do not rotate" : "rotate") +
                ", the scene's species now " + (gr.spin ? "rotate" : "do not"),
            "resume with the species' original 'rotates' keys");
  // The row count is the checkpoint's: grains may have been added or removed since the fill.
  const auto n_owned = in.value<std::uint64_t>("grains.n_owned");
  auto& bp = world.resources.get<BroadphaseState>();
  in.require_equal<double>("run.skin", in.value<double>("broadphase.skin"), bp.skin, "resume with the same run.skin");

  const auto n = in.value<std::uint64_t>("grains.n");
  // Every row takes at least 8 bytes per column: a larger count is corrupt, not a reason to allocate.
  in.require(n_owned <= n && n <= in.bytes() / 8, "grain counts", kFixResumeOrStateFile);
  gr.resize(n);
  gr.n_owned = n_owned;
  std::size_t k = 0;
  gr.for_each_core_column([&](auto& col) {
    const std::size_t rows = col.size();
    in.column(g(k++), col);
    if (col.size() != rows) in.fail("a grain column has the wrong length", same_scene);
  });
  k = 0;
  for (const RawColumn& c : gr.extras.raw_columns()) {
    // Attached columns are sized with the table; the checkpoint must hold exactly that many rows.
    if (!in.has(x(k))) in.fail("attached grain column " + std::to_string(k) + " is missing", same_scene);
    in.copy_raw(x(k++), c.data, c.elem_size, c.size);
  }
  if (in.has("grains.next_id")) {
    gr.next_id = in.value<std::int64_t>("grains.next_id");
    in.vector("grains.pending.insert", gr.pending.insert);
    in.vector("grains.pending.remove", gr.pending.remove);
  } else {  // written before ids were handed out during a run: the next free one
    gr.next_id = 0;
    for (std::size_t i = 0; i < gr.n; ++i) gr.next_id = std::max(gr.next_id, gr.pid.id[i] + 1);
    gr.pending = {};
  }

  restore_broadphase(in, bp, "");
  Walls& walls = world.resources.get<Walls>();
  walls.rotation_enabled = in.value<bool>("walls.rotation_enabled");
  walls.place(world.clock.t);
  restore_wall_loads(in, "walls.loads", walls.loads);
  if (MeshWallLoads* m = world.resources.find<MeshWallLoads>()) restore_wall_loads(in, "mesh_walls.loads", *m);
  list_sections(in, world.resources.get<NeighborList>(), world.resources.get<PairHistory>(), bp, "");
  restore_periodic_images(in, world.resources.get<PeriodicImages>(), gr);
  if (scene.flow.any())
    restore_flow_state(in, world.resources.get<FlowState>(), scene.flow);
  else if (in.has("flow.feeds"))
    in.fail("it was written by a run with [[feed]] or [[outlet]] tables, the scene now has none", same_scene);
  check_grains(in, gr, scene.species.size(), walls);
  check_list_sections(in, world.resources.get<NeighborList>(), world.resources.get<PairHistory>(), bp, gr);
}

}  // namespace gf
