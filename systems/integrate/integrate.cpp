#include "systems/integrate/integrate.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

namespace {

// One pass over the owned rows: v += h a, w += h alpha and, with Drift, x += dt v. Whole batches
// with vector loads (the columns are separate arrays, which the compiler cannot prove, so it would
// not vectorise the plain loop), the last partial batch row by row; padding rows are not touched.
template <bool Drift>
void kick_rows(Grains& g, const Gravity& grav, double h, double dt) {
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const std::size_t n = g.n_owned, full = n / L;
  const double gx = h * grav.x, gy = h * grav.y, gz = h * grav.z;
  auto row = [&](std::size_t i) {
    const double a = h * g.mass.inv_m[i];
    g.vel.x[i] += a * (g.force.x[i] + g.wall_force.x[i]) + gx;
    g.vel.y[i] += a * (g.force.y[i] + g.wall_force.y[i]) + gy;
    g.vel.z[i] += a * (g.force.z[i] + g.wall_force.z[i]) + gz;
    const double b = h * g.mass.inv_inertia[i];
    g.omega.x[i] += b * (g.torque.x[i] + g.wall_torque.x[i]);
    g.omega.y[i] += b * (g.torque.y[i] + g.wall_torque.y[i]);
    g.omega.z[i] += b * (g.torque.z[i] + g.wall_torque.z[i]);
    if constexpr (Drift) {
      g.pos.x[i] += dt * g.vel.x[i];
      g.pos.y[i] += dt * g.vel.y[i];
      g.pos.z[i] += dt * g.vel.z[i];
    }
  };
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, full, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    const B bh(h), bgx(gx), bgy(gy), bgz(gz), bdt(dt);
    auto ld = [](const ColumnD& c, std::size_t i) { return B::load_aligned(&c[i]); };
    for (std::size_t bt = r.begin(); bt != r.end(); ++bt) {
      const std::size_t i = bt * L;
      const B a = bh * ld(g.mass.inv_m, i);
      const B vx = ld(g.vel.x, i) + (a * (ld(g.force.x, i) + ld(g.wall_force.x, i)) + bgx);
      const B vy = ld(g.vel.y, i) + (a * (ld(g.force.y, i) + ld(g.wall_force.y, i)) + bgy);
      const B vz = ld(g.vel.z, i) + (a * (ld(g.force.z, i) + ld(g.wall_force.z, i)) + bgz);
      vx.store_aligned(&g.vel.x[i]);
      vy.store_aligned(&g.vel.y[i]);
      vz.store_aligned(&g.vel.z[i]);
      const B b = bh * ld(g.mass.inv_inertia, i);
      (ld(g.omega.x, i) + b * (ld(g.torque.x, i) + ld(g.wall_torque.x, i))).store_aligned(&g.omega.x[i]);
      (ld(g.omega.y, i) + b * (ld(g.torque.y, i) + ld(g.wall_torque.y, i))).store_aligned(&g.omega.y[i]);
      (ld(g.omega.z, i) + b * (ld(g.torque.z, i) + ld(g.wall_torque.z, i))).store_aligned(&g.omega.z[i]);
      if constexpr (Drift) {
        (ld(g.pos.x, i) + bdt * vx).store_aligned(&g.pos.x[i]);
        (ld(g.pos.y, i) + bdt * vy).store_aligned(&g.pos.y[i]);
        (ld(g.pos.z, i) + bdt * vz).store_aligned(&g.pos.z[i]);
      }
    }
  });
  for (std::size_t i = full * L; i < n; ++i) row(i);
}

}  // namespace

void kick(Grains& g, const Gravity& grav, double h) { kick_rows<false>(g, grav, h, 0.0); }

void kick_drift(Grains& g, const Gravity& grav, double h, double dt) { kick_rows<true>(g, grav, h, dt); }

void IntegratePositions::run(World& world) {
  if (world.resources.get<StepMode>().prime) return;
  kick_drift(world.grains, world.resources.get<Gravity>(), 0.5 * world.clock.dt, world.clock.dt);
}

void IntegrateVelocities::run(World& world) {
  if (world.resources.get<StepMode>().prime) return;
  kick(world.grains, world.resources.get<Gravity>(), 0.5 * world.clock.dt);
}

}  // namespace gf
