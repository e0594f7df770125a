#include "systems/mps/liquid_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "engine/machine_memory.hpp"
#include "systems/mps/liquid_fields.hpp"

namespace gf {

namespace {

bool multiple_of(double length, double l0) {
  const double k = length / l0;
  return std::abs(k - std::round(k)) < 1e-6 && std::round(k) >= 1;
}

void read_geometry(LiquidScene& s, const SceneNode& root) {
  const FieldTable& T = kLiquidGeometryFields;
  const SceneNode g = root.table("geometry");
  LiquidGeometry& geo = s.geometry;
  geo.dim = s.params.k.dim;
  const double l0 = s.params.k.l0;
  const std::string type = read_choice(g, T.field("type"), {"tank", "box", "channel", "pipe"});
  geo.kind = type == "tank"      ? LiquidGeometry::Kind::Tank
             : type == "box"     ? LiquidGeometry::Kind::Box
             : type == "channel" ? LiquidGeometry::Kind::Channel
                                 : LiquidGeometry::Kind::Pipe;
  const int min_layers = static_cast<int>(std::ceil(s.params.k.re / l0 - 1e-9));
  const Field& layers = T.field("layers");
  geo.layers = static_cast<int>(g.get_int(layers.key, std::max(3, min_layers), static_cast<std::int64_t>(layers.range.lo),
                                          static_cast<std::int64_t>(layers.range.hi)));
  if (geo.layers < min_layers)
    g.fail("layers", std::to_string(geo.layers) + " wall+dummy layers do not cover the kernel radius (" +
                         short_number(s.params.k.re / l0) + " l0): wall nodes would see a truncated neighbourhood",
           "set layers >= " + std::to_string(min_layers) + " or remove the key");
  if (geo.kind == LiquidGeometry::Kind::Pipe) {
    if (geo.dim != 3) g.fail("type", "a pipe needs liquid.dim = 3", "use type = \"channel\" in 2D");
    geo.center = g.get_vec3(T.field("center").key);
    geo.radius = read_number(g, T.field("radius"));
    const double len = read_number(g, T.field("length"));
    geo.lo = {geo.center[0], 0, 0};
    geo.hi = {geo.center[0] + len, 0, 0};
    if (geo.radius < 2 * l0) g.fail("radius", "the pipe is narrower than 4 particle spacings", "reduce liquid.l0");
  } else {
    geo.lo = g.get_vec3(T.field("lo").key);
    geo.hi = g.get_vec3(T.field("hi").key);
    for (int a = 0; a < geo.dim; ++a)
      if (!(geo.hi[a] > geo.lo[a])) g.fail("hi", "each component of hi must exceed lo's", "swap or correct lo and hi");
    if (geo.dim == 2 && (geo.lo[2] != 0 || geo.hi[2] != 0))
      g.fail("lo", "a 2D scene has no z extent", "set the z components of lo and hi to 0");
  }
  if (geo.kind == LiquidGeometry::Kind::Channel || geo.kind == LiquidGeometry::Kind::Pipe) {
    const double L = geo.hi[0] - geo.lo[0];
    if (!multiple_of(L, l0))
      g.fail(geo.kind == LiquidGeometry::Kind::Pipe ? "length" : "hi",
             "the periodic length along x (" + short_number(L) + " m) is not a whole number of spacings l0 = " + short_number(l0) + " m",
             "make it a multiple of l0, e.g. " + short_number(std::max(1.0, std::round(L / l0)) * l0) + " m");
    const double rc = s.params.k.re + s.params.skin;
    if (L < 3 * rc)
      g.fail(geo.kind == LiquidGeometry::Kind::Pipe ? "length" : "hi",
             "the periodic length " + short_number(L) + " m is shorter than 3 search radii (" + short_number(3 * rc) + " m)",
             "lengthen the periodic axis");
  }
  s.params.periodic = geo.periodicity();
  // The lattice of candidate nodes, counted in doubles before anything is made: a wrong extent (1e5 m
  // where 0.5 m was meant) would allocate without bound, and 1e30 m would overflow the indices. About
  // 1 kB per node with its neighbour pairs and solver rows; at most half the machine's memory.
  const double extent = geo.kind == LiquidGeometry::Kind::Pipe ? 2.0 * geo.radius : [&] {
    double e = std::numeric_limits<double>::infinity();
    for (int a = 0; a < geo.dim; ++a) e = std::min(e, geo.hi[a] - geo.lo[a]);
    return e;
  }();
  if (!(l0 < extent))
    root.table("liquid").fail("l0", "the particle spacing " + short_number(l0) + " m is not smaller than the "
                                    "geometry (" + short_number(extent) + " m across at its narrowest)",
                              "give l0 a fraction of the geometry, e.g. 1/20 of its height");
  std::array<double, 3> blo, bhi;
  geo.bounds(l0, blo, bhi);
  double cells = 1.0;
  for (int a = 0; a < geo.dim; ++a) cells *= (bhi[a] - blo[a]) / l0 + 2.0;
  const double most = static_cast<double>(half_of_memory()) / 1024.0;
  if (!(cells <= most))
    g.fail(geo.kind == LiquidGeometry::Kind::Pipe ? "length" : "hi",
           "the geometry's lattice has about " + short_number(cells) + " nodes of spacing l0 = " + short_number(l0) +
               " m, more than half this machine's memory holds (about " + short_number(most) + ")",
           "check the extent (m), or raise liquid.l0");
}

void read_fluid(LiquidScene& s, const SceneNode& root) {
  const auto blocks = root.tables("fluid");
  if (blocks.empty())
    root.fail("fluid", "the scene places no liquid", "add a [[fluid]] table with lo and hi (m) of a block to fill");
  s.fluid_line = blocks.front().line();
  for (const SceneNode& b : blocks) {
    FluidBlock fb;
    fb.lo = b.get_vec3(kFluidBlockFields.field("lo").key);
    fb.hi = b.get_vec3(kFluidBlockFields.field("hi").key);
    fb.velocity = b.get_vec3(kFluidBlockFields.field("velocity").key, {0, 0, 0});
    for (int a = 0; a < s.params.k.dim; ++a)
      if (!(fb.hi[a] > fb.lo[a])) b.fail("hi", "each component of hi must exceed lo's", "swap or correct lo and hi");
    s.blocks.push_back(fb);
  }
}


void read_solver(LiquidParams& p, const SceneNode& liq) {
  const auto sv = liq.maybe_table("solver");
  if (!sv) return;
  const FieldTable& T = kLiquidSolverFields;
  p.solver.kind = read_choice(*sv, T.field("kind"), {"parallel_cg", "eigen_cg"}) == "eigen_cg" ? PpeSolverKind::EigenCg
                                                                                                : PpeSolverKind::ParallelCg;
  const std::string pc = read_choice(*sv, T.field("preconditioner"), {"jacobi", "incomplete_cholesky", "multigrid"});
  p.solver.preconditioner = pc == "jacobi"      ? Preconditioner::Jacobi
                            : pc == "multigrid" ? Preconditioner::Multigrid
                                                : Preconditioner::IncompleteCholesky;
  if (p.solver.kind == PpeSolverKind::ParallelCg && pc == "incomplete_cholesky")
    sv->fail("preconditioner", "the parallel CG takes \"jacobi\" or \"multigrid\"",
             "use kind = \"eigen_cg\" for incomplete Cholesky, or choose one of those two");
  if (p.solver.kind == PpeSolverKind::EigenCg && pc == "multigrid")
    sv->fail("preconditioner", "the multigrid cycle preconditions the parallel CG only",
             "use kind = \"parallel_cg\" (the default) with it, or \"jacobi\" / \"incomplete_cholesky\" with eigen_cg");
  p.solver.tolerance = read_number(*sv, T.field("tolerance"));
  p.solver.max_iterations = static_cast<int>(read_integer(*sv, T.field("max_iterations")));
  p.solver.multigrid.reuse = static_cast<int>(read_integer(*sv, T.field("multigrid_reuse")));
  if (p.solver.multigrid.reuse != 1 && p.solver.preconditioner != Preconditioner::Multigrid)
    sv->fail("multigrid_reuse", "only the multigrid preconditioner has a hierarchy to reuse",
             "set preconditioner = \"multigrid\", or remove multigrid_reuse");
}

// liquid.turbulence, after the geometry: the mixing length needs a pipe's axis and radius.
void read_turbulence(LiquidScene& s, const SceneNode& root) {
  const SceneNode liq = root.table("liquid");
  if (read_choice(liq, kLiquidFields.field("turbulence"), {"none", "mixing_length"}) == "none") return;
  if (s.geometry.kind != LiquidGeometry::Kind::Pipe)
    liq.fail("turbulence", "the mixing length is defined by the distance from a pipe's wall",
             "use it with [geometry] type = \"pipe\", or use eddy_viscosity (a constant) in other geometries");
  s.params.mixing_length = {true, s.geometry.center[1], s.geometry.center[2], s.geometry.radius};
}

// [liquid]: the lattice, the material and the solver.
void read_liquid(LiquidParams& p, const SceneNode& root) {
  const FieldTable& T = kLiquidFields;
  const SceneNode liq = root.table("liquid");
  const int dim = static_cast<int>(read_integer(liq, T.field("dim")));
  const double l0 = read_number(liq, T.field("l0"));
  const double re = read_number(liq, T.field("re"));
  p.k = lattice_constants(dim, l0, re * l0);
  p.rho = read_number(liq, T.field("density"));  // kg/m^3, as a DEM species' bound
  p.nu = read_number(liq, T.field("viscosity"));
  p.eddy_viscosity = read_number(liq, T.field("eddy_viscosity"));
  p.gamma = read_number(liq, T.field("gamma"));
  p.beta = read_number(liq, T.field("surface_threshold"));
  p.free_surface = read_bool(liq, T.field("free_surface"));
  p.gradient = read_choice(liq, T.field("gradient"), {"sum", "min"}) == "sum" ? GradientForm::Sum : GradientForm::MinPressure;
  p.clip_negative = read_bool(liq, T.field("clip_negative"));
  p.compressibility = read_number(liq, T.field("compressibility"));
  p.collision.distance = read_number(liq, T.field("collision_distance")) * l0;
  p.collision.restitution = read_number(liq, T.field("collision_restitution"));
  p.skin = read_number(liq, T.field("skin")) * l0;
  read_solver(p, liq);
}

// An acceleration of [run]: three numbers, at most 1e6 m/s^2, none along z in 2D.
std::array<double, 3> read_acceleration(const SceneNode& run, std::string_view key) {
  const auto a = run.get_vec3(kLiquidRunFields.field(key).key, {0, 0, 0});
  require_acceleration(run, key, a);
  return a;
}

// [run]'s step, duration, accelerations and limits (its margin and velocity scale: after the geometry).
void read_run(LiquidScene& s, const SceneNode& run) {
  const FieldTable& T = kLiquidRunFields;
  LiquidParams& p = s.params;
  s.dt = read_number(run, T.field("dt"));
  s.duration = read_number(run, T.field("duration"));
  check_step_count(run, "duration", s.duration, s.dt);
  p.gravity = read_acceleration(run, "gravity");
  p.body_force = read_acceleration(run, "body_force");
  if (p.k.dim == 2 && (p.gravity[2] != 0 || p.body_force[2] != 0))
    run.fail(p.gravity[2] != 0 ? "gravity" : "body_force", "a 2D scene has no z component",
             "set the third component to 0");
  s.cfl_limit = read_number(run, T.field("cfl_limit"));
  s.diffusion_limit = read_number(run, T.field("diffusion_limit"));
  s.density_limit = read_number(run, T.field("density_limit"));
  s.allow_unstable_dt = read_bool(run, T.field("allow_unstable_dt"));
}

// Velocity scale for the CFL check: free fall over the liquid's height unless the scene states one.
void read_velocity_scale(LiquidScene& s, const SceneNode& run) {
  const std::array<double, 3>& gv = s.params.gravity;
  double height = 0;
  for (const FluidBlock& b : s.blocks) height = std::max(height, b.hi[1] - s.geometry.lo[1]);
  const double g = std::sqrt(gv[0] * gv[0] + gv[1] * gv[1] + gv[2] * gv[2]);
  const Field& f = kLiquidRunFields.field("velocity_scale");
  if (run.has(f.key)) {
    s.velocity_scale = read_number(run, f);
  } else {
    s.velocity_scale = std::sqrt(2.0 * g * std::max(height, 0.0));
    if (!(s.velocity_scale > 0))
      run.fail("velocity_scale", "no gravity to estimate the flow speed from",
               "set velocity_scale (m/s) to the largest speed expected, e.g. the analytic centre velocity");
  }
}

// The load-time CFL and diffusion numbers against their limits, unless the scene allows an unstable step.
void check_stability(LiquidScene& s, const SceneNode& run) {
  const double l0 = s.params.k.l0, nu = s.params.nu + s.params.eddy_viscosity;
  s.cfl = s.velocity_scale * s.dt / l0;
  s.diffusion = nu * s.dt / (l0 * l0);
  if (s.allow_unstable_dt) return;
  if (s.cfl > s.cfl_limit)
    run.fail("dt",
             "time step " + short_number(s.dt) + " s gives a CFL number " + short_number(s.cfl) + " (velocity scale " +
                 short_number(s.velocity_scale) + " m/s, l0 = " + short_number(l0) + " m) above cfl_limit = " + short_number(s.cfl_limit),
             "set dt <= " + short_number(s.cfl_limit * l0 / s.velocity_scale) +
                 ", or set allow_unstable_dt = true to run anyway");
  if (s.diffusion > s.diffusion_limit)
    run.fail("dt",
             "time step " + short_number(s.dt) + " s gives a viscous diffusion number (nu + eddy_viscosity) dt / l0^2 = " + short_number(s.diffusion) +
                 " above diffusion_limit = " + short_number(s.diffusion_limit),
             "set dt <= " + short_number(s.diffusion_limit * l0 * l0 / std::max(nu, 1e-300)) +
                 ", or set allow_unstable_dt = true to run anyway");
}

}  // namespace

std::int64_t LiquidScene::steps() const { return static_cast<std::int64_t>(std::llround(duration / dt)); }

StabilityLimits LiquidScene::limits() const {
  StabilityLimits lim;
  lim.cfl = cfl_limit;
  lim.density_ratio = density_limit;
  geometry.bounds(params.k.l0, lim.lo, lim.hi);
  for (int a = 0; a < 3; ++a) {
    lim.lo[a] -= domain_margin;
    lim.hi[a] += domain_margin;
  }
  // Periodic axes wrap: nothing leaves through them.
  if (params.periodic.axis >= 0) {
    lim.lo[params.periodic.axis] = -INFINITY;
    lim.hi[params.periodic.axis] = INFINITY;
  }
  return lim;
}

LiquidScene load_liquid_scene(const SceneDoc& doc, bool check_unused_keys) {
  LiquidScene s;
  s.file = doc.file();
  const SceneNode root = doc.root();
  read_liquid(s.params, root);
  const SceneNode run = root.table("run");
  read_run(s, run);
  read_geometry(s, root);
  read_turbulence(s, root);
  s.drive = read_flow_drive(root, s.params);  // after the geometry: its periodic axis
  read_fluid(s, root);
  const Field& margin = kLiquidRunFields.field("domain_margin");  // default: 10 l0, as the table says
  s.domain_margin = run.get_double(margin.key, 10 * s.params.k.l0, margin.range);
  read_velocity_scale(s, run);
  check_stability(s, run);
  if (auto out = root.maybe_table("output")) read_output_times(*out, s.dt, s.output);
  if (check_unused_keys) doc.check_all_used();
  return s;
}

}  // namespace gf
