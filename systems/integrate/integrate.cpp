#include "systems/integrate/integrate.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

void kick(Grains& g, const Gravity& grav, double h) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.n_owned, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    const double* fx = g.force.x.data();
    const double* fy = g.force.y.data();
    const double* fz = g.force.z.data();
    const double* wfx = g.wall_force.x.data();
    const double* wfy = g.wall_force.y.data();
    const double* wfz = g.wall_force.z.data();
    const double* tx = g.torque.x.data();
    const double* ty = g.torque.y.data();
    const double* tz = g.torque.z.data();
    const double* wtx = g.wall_torque.x.data();
    const double* wty = g.wall_torque.y.data();
    const double* wtz = g.wall_torque.z.data();
    const double* im = g.mass.inv_m.data();
    const double* ii = g.mass.inv_inertia.data();
    double* vx = g.vel.x.data();
    double* vy = g.vel.y.data();
    double* vz = g.vel.z.data();
    double* ox = g.omega.x.data();
    double* oy = g.omega.y.data();
    double* oz = g.omega.z.data();
    const double gx = h * grav.x, gy = h * grav.y, gz = h * grav.z;
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      const double a = h * im[i];
      vx[i] += a * (fx[i] + wfx[i]) + gx;
      vy[i] += a * (fy[i] + wfy[i]) + gy;
      vz[i] += a * (fz[i] + wfz[i]) + gz;
      const double b = h * ii[i];
      ox[i] += b * (tx[i] + wtx[i]);
      oy[i] += b * (ty[i] + wty[i]);
      oz[i] += b * (tz[i] + wtz[i]);
    }
  });
}

void drift(Grains& g, double dt) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.n_owned, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    double* x = g.pos.x.data();
    double* y = g.pos.y.data();
    double* z = g.pos.z.data();
    const double* vx = g.vel.x.data();
    const double* vy = g.vel.y.data();
    const double* vz = g.vel.z.data();
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      x[i] += dt * vx[i];
      y[i] += dt * vy[i];
      z[i] += dt * vz[i];
    }
  });
}

void IntegratePositions::run(World& world) {
  if (world.resources.get<StepMode>().prime) return;
  kick(world.grains, world.resources.get<Gravity>(), 0.5 * world.clock.dt);
  drift(world.grains, world.clock.dt);
}

void IntegrateVelocities::run(World& world) {
  if (world.resources.get<StepMode>().prime) return;
  kick(world.grains, world.resources.get<Gravity>(), 0.5 * world.clock.dt);
}

}  // namespace gf
