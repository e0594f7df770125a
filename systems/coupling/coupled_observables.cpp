#include "systems/coupling/coupled_observables.hpp"

#include <algorithm>
#include <cmath>

#include "systems/coupling/coupled_step.hpp"
#include "systems/mps/liquid_observables.hpp"

namespace gf {

namespace {

const std::vector<std::string> kGrainColumns = {
    "grains",     "grain_x",        "grain_y",     "grain_z",  "grain_vx",
    "grain_vy",   "grain_vz",       "grain_kinetic_energy",    "liquid_at_grain_vx",
    "liquid_at_grain_vy",           "liquid_at_grain_vz",      "grain_slip",
    "grain_liquid_fraction",        "min_liquid_fraction",     "liquid_force_x",
    "liquid_force_y",               "liquid_force_z",          "impulse_balance"};

double norm(const V3<double>& a) { return std::sqrt(dot(a, a)); }

}  // namespace

std::vector<std::string> coupled_series_columns() {
  std::vector<std::string> c = liquid_series_columns();
  c.insert(c.end(), kGrainColumns.begin(), kGrainColumns.end());
  return c;
}

std::vector<double> sample_coupled(World& w, const LiquidScene& liquid) {
  std::vector<double> row = sample_liquid(w, liquid);
  Grains& g = w.grains;
  const CouplingState& c = w.resources.get<CouplingState>();
  const LiquidAtGrain& at = g.extras.get<LiquidAtGrain>();
  const LiquidForce& f = g.extras.get<LiquidForce>();
  const std::size_t n = g.n_owned;
  V3<double> x{0, 0, 0}, v{0, 0, 0}, u{0, 0, 0}, force{0, 0, 0};
  double ke = 0, slip = 0, eps = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const V3<double> vi{g.vel.x[i], g.vel.y[i], g.vel.z[i]};
    x = x + V3<double>{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
    v = v + vi;
    force = force + V3<double>{f.x[i], f.y[i], f.z[i]};
    ke += 0.5 * g.mass.m[i] * dot(vi, vi);
    if (g.spin && g.mass.inv_inertia[i] > 0) {
      const V3<double> wi{g.omega.x[i], g.omega.y[i], g.omega.z[i]};
      ke += 0.5 * dot(wi, wi) / g.mass.inv_inertia[i];
    }
    const V3<double> ui{at.ux[i], at.uy[i], at.uz[i]};
    u = u + ui;
    slip += norm(ui - vi);
    eps += at.eps[i];
  }
  const double inv = n > 0 ? 1.0 / static_cast<double>(n) : NAN;
  const double min_eps = c.node_eps.empty() ? NAN : *std::min_element(c.node_eps.begin(), c.node_eps.end());
  const std::vector<double> grains = {static_cast<double>(n), inv * x.x, inv * x.y, inv * x.z, inv * v.x, inv * v.y,
                                      inv * v.z, ke, inv * u.x, inv * u.y, inv * u.z, inv * slip, inv * eps, min_eps, force.x, force.y, force.z,
                                      norm(c.grain_impulse + c.reaction_impulse)};
  row.insert(row.end(), grains.begin(), grains.end());
  return row;
}

}  // namespace gf
