#include "systems/mps/liquid_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <tuple>

#include "engine/clock_checkpoint.hpp"
#include "systems/mps/flow_drive.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/ppe.hpp"
#include "systems/mps/stability.hpp"

namespace gf {

namespace {

const std::string kSameScene =
    "resume with the liquid scene (and --set overrides) of the run that wrote it, or run this scene without --resume";

// Every FluidNodes column under a fixed name, for both directions.
template <class Io, class Nodes>
void node_sections(Io& io, Nodes& f) {
  io.column("liquid.node.x", f.x);
  io.column("liquid.node.y", f.y);
  io.column("liquid.node.z", f.z);
  io.column("liquid.node.u", f.u);
  io.column("liquid.node.v", f.v);
  io.column("liquid.node.w", f.w);
  io.column("liquid.node.p", f.p);
  io.column("liquid.node.n", f.n);
  io.column("liquid.node.div", f.div);
  io.column("liquid.node.ax", f.ax);
  io.column("liquid.node.ay", f.ay);
  io.column("liquid.node.az", f.az);
  io.column("liquid.node.surface", f.surface);
}

template <class Io, class Pairs>
void pair_sections(Io& io, Pairs& nb) {
  io.vector("liquid.neighbors.start", nb.start);
  io.vector("liquid.neighbors.j", nb.j);
  io.vector("liquid.neighbors.image", nb.image);
  io.vector("liquid.neighbors.w", nb.w);
  io.vector("liquid.neighbors.x0", nb.x0);
  io.vector("liquid.neighbors.y0", nb.y0);
  io.vector("liquid.neighbors.z0", nb.z0);
}

// One value in either direction.
void io_value(CheckpointWriter& out, const std::string& name, const auto& v) { out.value(name, v); }
template <class T>
void io_value(const CheckpointReader& in, const std::string& name, T& v) {
  v = in.value<T>(name);
}

// The last step's diagnostics (the series' max_speed, cfl, ppe columns), field by field.
template <class Io, class Diagnostics>
void diagnostic_sections(Io& io, Diagnostics& d) {
  io_value(io, "liquid.diagnostics.max_speed", d.max_speed);
  io_value(io, "liquid.diagnostics.cfl", d.cfl);
  io_value(io, "liquid.diagnostics.max_density_ratio", d.max_density_ratio);
  io_value(io, "liquid.diagnostics.surface_nodes", d.surface_nodes);
  io_value(io, "liquid.diagnostics.ppe.iterations", d.ppe.iterations);
  io_value(io, "liquid.diagnostics.ppe.residual", d.ppe.residual);
  io_value(io, "liquid.diagnostics.ppe.converged", d.ppe.converged);
  io_value(io, "liquid.diagnostics.ppe.unknowns", d.ppe.unknowns);
  io_value(io, "liquid.diagnostics.ppe.closed", d.ppe.closed);
}

void require_same(const CheckpointReader& in, const std::string& what, const std::string& stored,
                  const std::string& now, const std::string& fix) {
  if (stored != now) in.fail("it was written with " + what + " = " + stored + ", the scene now gives " + now, fix);
}

void check_scene(const CheckpointReader& in, const FluidNodes& f, const LiquidScene& scene) {
  if (!in.has("liquid.nodes"))
    in.fail("it holds no liquid state (a DEM scene's run wrote it)",
            "resume a liquid scene from a checkpoint its own run wrote (<out>/checkpoints/checkpoint.gfc)");
  require_same(in, "liquid.dim", std::to_string(in.value<int>("liquid.dim")), std::to_string(scene.params.k.dim),
               kSameScene);
  require_same(in, "liquid.l0", short_number(in.value<double>("liquid.l0")), short_number(scene.params.k.l0),
               kSameScene);
  require_same(in, "nodes (fluid, wall, dummy)",
               std::to_string(in.value<std::uint64_t>("liquid.nodes")) + " (" +
                   std::to_string(in.value<std::uint64_t>("liquid.fluid_nodes")) + " fluid)",
               std::to_string(f.size()) + " (" + std::to_string(f.count(kFluid)) + " fluid)", kSameScene);
  Column<std::int32_t> kind;
  in.column("liquid.node.kind", kind);
  if (kind.size() != f.size() || !std::equal(kind.begin(), kind.end(), f.kind.begin()))
    in.fail("its node lattice (fluid, wall and dummy rows) differs from the one the scene makes", kSameScene);
}

void check_pairs(const CheckpointReader& in, const NeighborPairs& nb, std::size_t rows) {
  const std::size_t pairs = nb.j.size();
  in.require(nb.start.empty() || (nb.start.size() == rows + 1 && nb.start.front() == 0 && nb.start.back() == pairs &&
                                   std::is_sorted(nb.start.begin(), nb.start.end())),
             "neighbour list offsets", kFixResume);
  in.require(nb.image.size() == pairs && (nb.w.empty() || nb.w.size() == pairs), "neighbour list lengths", kFixResume);
  in.require(std::all_of(nb.j.begin(), nb.j.end(), [rows](std::uint32_t q) { return q < rows; }),
             "neighbour list rows", kFixResume);
  in.require(nb.x0.size() == nb.y0.size() && nb.y0.size() == nb.z0.size() && (nb.x0.empty() || nb.x0.size() == rows),
             "neighbour reference positions", kFixResume);
}

}  // namespace

void save_liquid_state(CheckpointWriter& out, World& world, const LiquidScene& scene) {
  save_clock(out, world.clock);
  save_liquid_nodes(out, world, scene);
}

void restore_liquid_state(const CheckpointReader& in, World& world, const LiquidScene& scene) {
  restore_liquid_nodes(in, world, scene);  // refuses another scene's checkpoint first
  if (in.value<double>("clock.dt") != scene.dt)
    require_same(in, "run.dt", short_number(in.value<double>("clock.dt")), short_number(scene.dt),
                 "resume with the same run.dt: a checkpoint continues a run, it does not change its step");
  restore_clock(in, world.clock);
  in.require(world.clock.step >= 0, "the step count is negative", kFixResume);
}

void save_liquid_nodes(CheckpointWriter& out, World& world, const LiquidScene& scene) {
  FluidNodes& f = world.tables.get<FluidNodes>();
  out.value("liquid.dim", scene.params.k.dim);
  out.value("liquid.l0", scene.params.k.l0);
  out.value("liquid.nodes", static_cast<std::uint64_t>(f.size()));
  out.value("liquid.fluid_nodes", static_cast<std::uint64_t>(f.count(kFluid)));
  out.column("liquid.node.kind", f.kind);
  node_sections(out, f);
  NeighborPairs& nb = world.resources.get<NeighborPairs>();
  pair_sections(out, nb);
  out.value("liquid.neighbors.radius", nb.radius);
  out.value("liquid.neighbors.builds", nb.builds);
  // Field by field: the structs' padding bytes are unset, and the checkpoint of a run in two pieces must match
  // the uninterrupted run's byte for byte.
  out.value("liquid.neighbors.periodic.axis", nb.periodic.axis);
  out.value("liquid.neighbors.periodic.lo", nb.periodic.lo);
  out.value("liquid.neighbors.periodic.hi", nb.periodic.hi);
  diagnostic_sections(out, world.resources.get<LiquidDiagnostics>());
  // The body force a [drive] controls changes during the run.
  const auto& force = world.resources.get<LiquidParams>().body_force;
  for (std::size_t c = 0; c < 3; ++c) out.value("liquid.body_force." + std::to_string(c), force[c]);
  if (const FlowDrive* d = world.resources.find<FlowDrive>()) out.value("liquid.drive.last_mean", d->last_mean);
  // A resumed run builds its multigrid hierarchy at its first solve; so does the run that wrote this.
  if (PpeWorkspace* ws = world.resources.find<PpeWorkspace>()) multigrid_invalidate(ws->multigrid);
}

void restore_liquid_nodes(const CheckpointReader& in, World& world, const LiquidScene& scene) {
  FluidNodes& f = world.tables.get<FluidNodes>();
  check_scene(in, f, scene);
  const std::size_t rows = f.size();
  node_sections(in, f);
  std::size_t wrong = 0;
  std::apply([&](auto&... c) { ((wrong += c.size() != rows), ...); }, f.columns());
  in.require(wrong == 0, "a node column has the wrong length", kFixResume);
  for (const ColumnD* c : {&f.x, &f.y, &f.z, &f.u, &f.v, &f.w, &f.p, &f.n})
    in.require(std::all_of(c->begin(), c->end(), [](double v) { return std::isfinite(v); }),
               "a node's position, velocity, pressure or number density is not finite", kFixResume);
  NeighborPairs& nb = world.resources.get<NeighborPairs>();
  pair_sections(in, nb);
  check_pairs(in, nb, rows);
  nb.radius = in.value<double>("liquid.neighbors.radius");
  nb.builds = in.value<std::int64_t>("liquid.neighbors.builds");
  nb.periodic.axis = in.value<int>("liquid.neighbors.periodic.axis");
  nb.periodic.lo = in.value<double>("liquid.neighbors.periodic.lo");
  nb.periodic.hi = in.value<double>("liquid.neighbors.periodic.hi");
  in.require(nb.periodic.axis >= -1 && nb.periodic.axis <= 2, "the periodic axis", kFixResume);
  diagnostic_sections(in, world.resources.get<LiquidDiagnostics>());
  auto& force = world.resources.get<LiquidParams>().body_force;
  for (std::size_t c = 0; c < 3; ++c)
    if (in.has("liquid.body_force." + std::to_string(c))) force[c] = in.value<double>("liquid.body_force." + std::to_string(c));
  in.require(std::all_of(force.begin(), force.end(), [](double v) { return std::isfinite(v); }), "the body force is not finite", kFixResume);
  if (FlowDrive* d = world.resources.find<FlowDrive>(); d && in.has("liquid.drive.last_mean")) {
    d->last_mean = in.value<double>("liquid.drive.last_mean");  // NaN before the first control step
    in.require(!std::isinf(d->last_mean), "the drive's last mean velocity is not finite", kFixResume);
  }
}

}  // namespace gf
