#include "systems/walls/wall_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "systems/contact/linear_spring_dashpot.hpp"
#include "systems/integrate/integrate.hpp"

namespace gf {

void compute_wall_forces(Grains& g, Walls& walls, WallHistory& h, const ContactTable& table, double dt,
                         double t_contact) {
  walls.place(t_contact);
  const std::size_t nw = walls.list.size();
  if (h.cols.size() != 6 * nw) {
    h.cols.resize(6 * nw);
    for (auto& c : h.cols) c.resize(g.n);
  }
  const PairCoeffs* coeffs = table.wall_data();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.n_owned, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3d p{g.pos.x[i], g.pos.y[i], g.pos.z[i]};
      const double ri = g.radius.r[i];
      Vec3d f{0, 0, 0}, t{0, 0, 0};
      for (std::size_t w = 0; w < nw; ++w) {
        const Wall& wall = walls.list[w];
        ColumnD* hc = &h.cols[6 * w];
        Vec3d n;
        const double gap = wall_gap(wall, p, n);
        if (gap >= ri) {
          for (int c = 0; c < 6; ++c) hc[c][i] = 0.0;
          continue;
        }
        const double delta = ri - gap;
        const double li = ri - 0.5 * delta;
        const Vec3d wi{g.omega.x[i], g.omega.y[i], g.omega.z[i]};
        const Vec3d contact = p + li * n;
        const double om = walls.rotation_enabled ? wall.omega : 0.0;
        const Vec3d wall_w = om * wall.rot_axis;
        const Vec3d wall_v = cross(wall_w, contact - wall.rot_point);
        const Vec3d v = Vec3d{g.vel.x[i], g.vel.y[i], g.vel.z[i]} + cross(li * wi, n) - wall_v;
        const PairCoeffs& pc = coeffs[static_cast<std::size_t>(g.species.type[i])];
        const LsdCoeffs<double> c{pc.kn, pc.kt, pc.kr, pc.eta_n, pc.eta_t, pc.eta_r, pc.fs, pc.fr};
        LsdState<double> s{{hc[0][i], hc[1][i], hc[2][i]}, {hc[3][i], hc[4][i], hc[5][i]}};
        const LsdResult<double> res = LinearSpringDashpot::evaluate(true, n, delta, v, wi - wall_w, c, dt, s);
        hc[0][i] = s.shear.x;
        hc[1][i] = s.shear.y;
        hc[2][i] = s.shear.z;
        hc[3][i] = s.roll.x;
        hc[4][i] = s.roll.y;
        hc[5][i] = s.roll.z;
        f = f + res.force;
        t = t + li * cross(n, res.force_t) + res.rolling_torque;
      }
      g.wall_force.x[i] = f.x;
      g.wall_force.y[i] = f.y;
      g.wall_force.z[i] = f.z;
      g.wall_torque.x[i] = t.x;
      g.wall_torque.y[i] = t.y;
      g.wall_torque.z[i] = t.z;
    }
  });
}

void WallContact::run(World& world) {
  // Positions were advanced by the first half of the step: they refer to t + dt.
  const bool prime = world.resources.get<StepMode>().prime;
  const double t = world.clock.t + (prime ? 0.0 : world.clock.dt);
  compute_wall_forces(world.grains, world.resources.get<Walls>(), world.grains.extras.get<WallHistory>(),
                      world.resources.get<ContactTable>(), world.clock.dt, t);
}

}  // namespace gf
