#include "systems/coupling/coupled_step.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "systems/integrate/integrate.hpp"

namespace gf {

namespace {

std::span<const double> owned(const ColumnD& c, std::size_t n) { return {c.data(), n}; }

struct LiquidForceSystem : SystemBase<LiquidForceSystem> {
  using Reads = gf::Reads<Velocity, AngularVelocity, Radius, LiquidAtGrain, Gravity, CouplingState>;
  using Writes = gf::Writes<LiquidForce, LiquidImpulse, LiquidTorque>;
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
      V3<double> F = liquid_force(u, v, at.eps[i], 2.0 * g.radius.r[i], c.liquid.props, gv, *c.drag);
      if (c.shear_lift || c.spin_lift) F = F + lift(g, at, c, i, u - v);
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
    if (c.rotational_drag) set_torques(g, c);
  }
  // Shear and spin lift from the slip and the liquid's curl at the step's start, and the grain's spin now.
  static V3<double> lift(const Grains& g, const LiquidAtGrain& at, const CouplingState& c, std::size_t i,
                         const V3<double>& slip) {
    const V3<double> W{at.curl_x[i], at.curl_y[i], at.curl_z[i]};
    const double d = 2.0 * g.radius.r[i];
    V3<double> F{0, 0, 0};
    if (c.shear_lift) F = F + shear_lift(slip, W, d, c.liquid.props);
    if (c.spin_lift) {
      const V3<double> rel{0.5 * W.x - g.omega.x[i], 0.5 * W.y - g.omega.y[i], 0.5 * W.z - g.omega.z[i]};
      F = F + spin_lift(slip, rel, d, c.liquid.props);
    }
    return F;
  }
  // T = rotational drag on the spin relative to half the liquid's curl at the step's start.
  static void set_torques(Grains& g, const CouplingState& c) {
    LiquidTorque& t = g.extras.get<LiquidTorque>();
    const LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
    for (std::size_t i = 0; i < g.n_owned; ++i) {
      const V3<double> rel{g.omega.x[i] - 0.5 * at.curl_x[i], g.omega.y[i] - 0.5 * at.curl_y[i],
                           g.omega.z[i] - 0.5 * at.curl_z[i]};
      const V3<double> T = rotational_drag_torque(rel, 2.0 * g.radius.r[i], c.liquid.props);
      t.x[i] = T.x;
      t.y[i] = T.y;
      t.z[i] = T.z;
    }
  }
};

}  // namespace

namespace coupling_detail {

std::vector<double> share_grains(const Grains& g, const PointSet& carriers, const std::vector<std::uint32_t>* rows,
                                 CouplingState& c) {
  const std::size_t n = g.n_owned;
  const PointSet grains{owned(g.pos.x, n), owned(g.pos.y, n), owned(g.pos.z, n)};
  const LiquidFacts& l = c.liquid;
  auto shares = [&](const PointSet& nodes) {
    return l.periodic_axis >= 0 ? compute_shares_periodic(grains, nodes, c.h, l.periodic_axis, l.period_lo, l.period_hi)
                                : compute_shares(grains, nodes, c.h);
  };
  if (!rows) {
    c.shares = shares(carriers);
  } else {
    std::vector<double> x, y, z;
    for (const std::uint32_t i : *rows) {
      x.push_back(carriers.x[i]);
      y.push_back(carriers.y[i]);
      z.push_back(carriers.z[i]);
    }
    c.shares = shares({x, y, z});
    for (std::uint32_t& k : c.shares.node) k = (*rows)[k];
  }
  std::vector<double> volume(n);
  for (std::size_t i = 0; i < n; ++i) volume[i] = 4.0 / 3.0 * std::numbers::pi * std::pow(g.radius.r[i], 3);
  return solid_volume(c.shares, volume, carriers.size());
}

void sample_at_grains(Grains& g, const CouplingState& c, const PointSet& carriers, const PointSet& velocity) {
  const std::vector<double> eps = at_grains(c.shares, c.node_eps);
  std::vector<V3<double>> curl;
  if (c.needs_curl()) {
    const std::size_t n = g.n_owned;
    const PointSet grains{owned(g.pos.x, n), owned(g.pos.y, n), owned(g.pos.z, n)};
    curl = curl_at_grains(c.shares, grains, carriers, velocity, {c.liquid.periodic_axis, c.liquid.period_lo, c.liquid.period_hi});
  }
  const std::vector<double> ux = at_grains(c.shares, velocity.x);
  const std::vector<double> uy = at_grains(c.shares, velocity.y);
  const std::vector<double> uz = at_grains(c.shares, velocity.z);
  LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
  LiquidImpulse& j = g.extras.get<LiquidImpulse>();
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    at.ux[i] = ux[i];
    at.uy[i] = uy[i];
    at.uz[i] = uz[i];
    at.eps[i] = eps[i];
    const V3<double> w = curl.empty() ? V3<double>{0, 0, 0} : curl[i];
    at.curl_x[i] = w.x;
    at.curl_y[i] = w.y;
    at.curl_z[i] = w.z;
    at.row[i] = static_cast<std::int32_t>(i);
    j.x[i] = j.y[i] = j.z[i] = 0.0;
  }
}

std::vector<V3<double>> reaction_per_volume(Grains& g, CouplingState& c, std::size_t carriers) {
  const LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
  const LiquidImpulse& j = g.extras.get<LiquidImpulse>();
  std::vector<V3<double>> impulse(g.n_owned, V3<double>{0, 0, 0});
  c.grain_impulse = {0, 0, 0};
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    impulse[static_cast<std::size_t>(at.row[i])] = {j.x[i], j.y[i], j.z[i]};
    c.grain_impulse = c.grain_impulse + impulse[static_cast<std::size_t>(at.row[i])];
  }
  std::vector<V3<double>> per_volume(carriers);
  spread_reaction(c.shares, impulse, c.liquid.carrier_volume, per_volume);
  return per_volume;
}

}  // namespace coupling_detail

void attach_coupling(const CouplingSpec& coupling, const LiquidFacts& liquid, World& w) {
  const std::size_t n = w.grains.rows();
  w.grains.extras.attach<LiquidForce>(n);
  w.grains.extras.attach<LiquidAtGrain>(n);
  w.grains.extras.attach<LiquidImpulse>(n);
  w.grains.extras.attach<LiquidTorque>(n);
  CouplingState& c = w.resources.emplace<CouplingState>();
  c.h = coupling.smoothing_radius;
  c.drag = coupling.drag;
  c.rotational_drag = coupling.rotational_drag;
  c.shear_lift = coupling.shear_lift;
  c.spin_lift = coupling.spin_lift;
  c.eps_min = coupling.min_liquid_fraction;
  c.liquid = liquid;
  c.fluid_nodes_only = coupling.fluid_nodes_only;
}

ForceTerm liquid_force_term(const CouplingSpec& coupling) {
  return coupling.rotational_drag ? force_term<LiquidForce, LiquidTorque>("liquid_force")
                                  : force_term<LiquidForce>("liquid_force");
}

void add_liquid_force(Schedule& step) { step.emplace<LiquidForceSystem>(); }

std::unique_ptr<Schedule> fixed_grains_step() {
  auto step = std::make_unique<Schedule>();
  step->emplace<LiquidForceSystem>();
  return step;
}

}  // namespace gf
