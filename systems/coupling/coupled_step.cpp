#include "systems/coupling/coupled_step.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "engine/sub_schedule.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_fraction.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/liquid_step.hpp"

namespace gf {

namespace {

std::span<const double> owned(const ColumnD& c, std::size_t n) { return {c.data(), n}; }

struct CouplingPrepare : SystemBase<CouplingPrepare> {
  using Reads = gf::Reads<Position, Radius, FluidNodes>;
  using Writes = gf::Writes<LiquidAtGrain, LiquidImpulse, CouplingState, LiquidFraction>;
  std::string_view name() const override { return "coupling_prepare"; }
  void run(World& w, const StepContext&) override { prepare_coupling(w); }
};

struct LiquidForceSystem : SystemBase<LiquidForceSystem> {
  using Reads = gf::Reads<Velocity, Radius, LiquidAtGrain, Gravity, CouplingState>;
  using Writes = gf::Writes<LiquidForce, LiquidImpulse>;
  std::string_view name() const override { return "liquid_force"; }
  void run(World& w, const StepContext& step) override {
    Grains& g = w.grains;
    const CouplingState& c = w.resources.get<CouplingState>();
    const Gravity& grav = w.resources.get<Gravity>();
    const V3<double> gv{grav.x, grav.y, grav.z};
    LiquidForce& f = g.extras.get<LiquidForce>();
    LiquidImpulse& j = g.extras.get<LiquidImpulse>();
    const LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
    const double half = 0.5 * step.dt;
    for (std::size_t i = 0; i < g.n_owned; ++i) {
      const V3<double> u{at.ux[i], at.uy[i], at.uz[i]}, v{g.vel.x[i], g.vel.y[i], g.vel.z[i]};
      const V3<double> F = liquid_force(u, v, at.eps[i], 2.0 * g.radius.r[i], c.liquid, gv, *c.drag);
      if (!step.prime) {
        // The integrator's closing half-kick of this sub-step uses F, its opening one the force before.
        j.x[i] += half * (f.x[i] + F.x);
        j.y[i] += half * (f.y[i] + F.y);
        j.z[i] += half * (f.z[i] + F.z);
      }
      f.x[i] = F.x;
      f.y[i] = F.y;
      f.z[i] = F.z;
    }
  }
};

struct LiquidReaction : SystemBase<LiquidReaction> {
  using Reads = gf::Reads<LiquidAtGrain, LiquidImpulse, LiquidParams>;
  using Writes = gf::Writes<FluidNodes, CouplingState>;
  std::string_view name() const override { return "liquid_reaction"; }
  void run(World& w, const StepContext&) override {
    Grains& g = w.grains;
    CouplingState& c = w.resources.get<CouplingState>();
    FluidNodes& f = w.tables.get<FluidNodes>();
    const LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
    const LiquidImpulse& j = g.extras.get<LiquidImpulse>();
    std::vector<V3<double>> impulse(g.n_owned, V3<double>{0, 0, 0});
    c.grain_impulse = {0, 0, 0};
    for (std::size_t i = 0; i < g.n_owned; ++i) {
      impulse[static_cast<std::size_t>(at.row[i])] = {j.x[i], j.y[i], j.z[i]};
      c.grain_impulse = c.grain_impulse + impulse[static_cast<std::size_t>(at.row[i])];
    }
    std::vector<V3<double>> per_volume(f.size());
    spread_reaction(c.shares, impulse, c.node_volume, per_volume);
    const double mass = c.liquid.density * c.node_volume;
    c.reaction_impulse = c.fluid_reaction = {0, 0, 0};
    for (std::size_t n = 0; n < f.size(); ++n) {
      const V3<double> dp = c.node_volume * per_volume[n];
      c.reaction_impulse = c.reaction_impulse + dp;
      if (f.kind[n] != kFluid) continue;
      c.fluid_reaction = c.fluid_reaction + dp;
      f.u[n] += dp.x / mass;
      f.v[n] += dp.y / mass;
      f.w[n] += dp.z / mass;
    }
  }
};

// The grains' shares over every node, or over the fluid nodes only (renumbered back to node rows).
GrainShares node_shares(const PointSet& grains, const FluidNodes& f, const CouplingState& c) {
  const Periodicity& per = c.periodic;
  auto shares = [&](const PointSet& nodes) {
    return per.axis >= 0 ? compute_shares_periodic(grains, nodes, c.h, per.axis, per.lo, per.hi)
                         : compute_shares(grains, nodes, c.h);
  };
  if (!c.fluid_nodes_only) return shares({owned(f.x, f.size()), owned(f.y, f.size()), owned(f.z, f.size())});
  std::vector<std::uint32_t> row;
  std::vector<double> x, y, z;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid) {
      row.push_back(static_cast<std::uint32_t>(i));
      x.push_back(f.x[i]);
      y.push_back(f.y[i]);
      z.push_back(f.z[i]);
    }
  GrainShares s = shares({x, y, z});
  for (std::uint32_t& n : s.node) n = row[n];
  return s;
}

}  // namespace

void prepare_coupling(World& w) {
  Grains& g = w.grains;
  CouplingState& c = w.resources.get<CouplingState>();
  const FluidNodes& f = w.tables.get<FluidNodes>();
  const std::size_t n = g.n_owned;
  const PointSet grains{owned(g.pos.x, n), owned(g.pos.y, n), owned(g.pos.z, n)};
  c.shares = node_shares(grains, f, c);
  std::vector<double> volume(n);
  for (std::size_t i = 0; i < n; ++i) volume[i] = 4.0 / 3.0 * std::numbers::pi * std::pow(g.radius.r[i], 3);
  const std::vector<double> solid = solid_volume(c.shares, volume, f.size());
  LiquidFraction* averaged = w.resources.find<LiquidFraction>();
  if (averaged) {  // the nodes thin out where grains are: each stands for its own volume of mixture
    const std::vector<double> mixture = mixture_volumes(owned(f.n, f.size()), w.resources.get<LiquidParams>().k.n0, c.node_volume);
    c.node_eps = liquid_fraction(solid, mixture, c.eps_min);
    averaged->eps = c.node_eps;
  } else {
    c.node_eps = liquid_fraction(solid, c.node_volume, c.eps_min);
  }
  const std::vector<double> eps = at_grains(c.shares, c.node_eps);
  const std::vector<double> ux = at_grains(c.shares, owned(f.u, f.size()));
  const std::vector<double> uy = at_grains(c.shares, owned(f.v, f.size()));
  const std::vector<double> uz = at_grains(c.shares, owned(f.w, f.size()));
  LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
  LiquidImpulse& j = g.extras.get<LiquidImpulse>();
  for (std::size_t i = 0; i < n; ++i) {
    at.ux[i] = ux[i];
    at.uy[i] = uy[i];
    at.uz[i] = uz[i];
    at.eps[i] = eps[i];
    at.row[i] = static_cast<std::int32_t>(i);
    j.x[i] = j.y[i] = j.z[i] = 0.0;
  }
}

void attach_coupling(const CouplingSpec& coupling, const LiquidScene& liquid, World& w) {
  const std::size_t n = w.grains.rows();
  w.grains.extras.attach<LiquidForce>(n);
  w.grains.extras.attach<LiquidAtGrain>(n);
  w.grains.extras.attach<LiquidImpulse>(n);
  CouplingState& c = w.resources.emplace<CouplingState>();
  c.h = coupling.smoothing_radius;
  c.drag = coupling.drag;
  c.eps_min = coupling.min_liquid_fraction;
  c.node_volume = std::pow(liquid.params.k.l0, 3);
  c.periodic = liquid.params.periodic;
  c.fluid_nodes_only = coupling.fluid_nodes_only;
  c.liquid = {liquid.params.rho, liquid.params.rho * liquid.params.nu};
  if (coupling.averaged) w.resources.emplace<LiquidFraction>();
}

ForceTerm liquid_force_term() { return force_term<LiquidForce>("liquid_force"); }

void add_liquid_force(Schedule& step) { step.emplace<LiquidForceSystem>(); }

std::unique_ptr<Schedule> fixed_grains_step() {
  auto step = std::make_unique<Schedule>();
  step->emplace<LiquidForceSystem>();
  return step;
}

SubSchedule& schedule_coupled_step(Schedule& outer, std::unique_ptr<Schedule> inner, int substeps, bool driven) {
  outer.emplace<CouplingPrepare>();
  SubSchedule& dem = outer.emplace<SubSchedule>("dem_substeps", substeps, std::move(inner));
  outer.emplace<LiquidReaction>();
  schedule_liquid_step(outer, driven);
  return dem;
}

}  // namespace gf
