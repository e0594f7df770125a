#include "systems/contact/pair_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "systems/contact/linear_spring_dashpot.hpp"

namespace gf {

void compute_pair_forces(Grains& g, const NeighborList& list, PairHistory& h, const ContactTable& table, double dt,
                         PairForces& out) {
  const std::size_t np = list.pairs();
  for_each_column(out, [np](ColumnD& col) { col.resize(np); });
  const std::size_t ntypes = table.types();
  const PairCoeffs* coeffs = table.pair_data();

  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, np, 2048), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k != r.end(); ++k) {
      const std::uint32_t i = list.i[k], j = list.j[k];
      const V3<double> d{g.pos.x[j] - g.pos.x[i], g.pos.y[j] - g.pos.y[i], g.pos.z[j] - g.pos.z[i]};
      const double ri = g.radius.r[i], rj = g.radius.r[j];
      const double dist2 = dot(d, d);
      const double rsum = ri + rj;
      const bool touching = dist2 < rsum * rsum;
      if (!touching) {
        // Apart: springs reset, nothing to sum. Skipping the law keeps the common case cheap.
        h.sx[k] = h.sy[k] = h.sz[k] = h.rx[k] = h.ry[k] = h.rz[k] = 0.0;
        out.fx[k] = out.fy[k] = out.fz[k] = 0.0;
        out.tix[k] = out.tiy[k] = out.tiz[k] = 0.0;
        out.tjx[k] = out.tjy[k] = out.tjz[k] = 0.0;
        continue;
      }
      const double dist = std::sqrt(dist2);
      const double inv = 1.0 / dist;
      const V3<double> n{d.x * inv, d.y * inv, d.z * inv};
      const double delta = rsum - dist;
      const double li = ri - 0.5 * delta, lj = rj - 0.5 * delta;
      const V3<double> wi{g.omega.x[i], g.omega.y[i], g.omega.z[i]};
      const V3<double> wj{g.omega.x[j], g.omega.y[j], g.omega.z[j]};
      const V3<double> vij{g.vel.x[i] - g.vel.x[j], g.vel.y[i] - g.vel.y[j], g.vel.z[i] - g.vel.z[j]};
      const V3<double> v = vij + cross(li * wi + lj * wj, n);
      const PairCoeffs& pc =
          coeffs[static_cast<std::size_t>(g.species.type[i]) * ntypes + static_cast<std::size_t>(g.species.type[j])];
      const LsdCoeffs<double> c{pc.kn, pc.kt, pc.kr, pc.eta_n, pc.eta_t, pc.eta_r, pc.fs, pc.fr};
      LsdState<double> s{{h.sx[k], h.sy[k], h.sz[k]}, {h.rx[k], h.ry[k], h.rz[k]}};
      const LsdResult<double> res = LinearSpringDashpot::evaluate(true, n, delta, v, wi - wj, c, dt, s);
      h.sx[k] = s.shear.x;
      h.sy[k] = s.shear.y;
      h.sz[k] = s.shear.z;
      h.rx[k] = s.roll.x;
      h.ry[k] = s.roll.y;
      h.rz[k] = s.roll.z;
      const V3<double> nxf = cross(n, res.force_t);
      out.fx[k] = res.force.x;
      out.fy[k] = res.force.y;
      out.fz[k] = res.force.z;
      out.tix[k] = li * nxf.x + res.rolling_torque.x;
      out.tiy[k] = li * nxf.y + res.rolling_torque.y;
      out.tiz[k] = li * nxf.z + res.rolling_torque.z;
      // On j the force is -F and the lever -L_j n: the tangential torque has the same sign as i's.
      out.tjx[k] = lj * nxf.x - res.rolling_torque.x;
      out.tjy[k] = lj * nxf.y - res.rolling_torque.y;
      out.tjz[k] = lj * nxf.z - res.rolling_torque.z;
    }
  });

  const std::size_t nown = g.n_owned;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nown, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t a = r.begin(); a != r.end(); ++a) {
      double fx = 0, fy = 0, fz = 0, tx = 0, ty = 0, tz = 0;
      for (std::uint32_t k = list.offsets[a]; k < list.offsets[a + 1]; ++k) {
        fx += out.fx[k];
        fy += out.fy[k];
        fz += out.fz[k];
        tx += out.tix[k];
        ty += out.tiy[k];
        tz += out.tiz[k];
      }
      for (std::uint32_t q = list.in_offsets[a]; q < list.in_offsets[a + 1]; ++q) {
        const std::uint32_t k = list.in_pairs[q];
        fx -= out.fx[k];
        fy -= out.fy[k];
        fz -= out.fz[k];
        tx += out.tjx[k];
        ty += out.tjy[k];
        tz += out.tjz[k];
      }
      g.force.x[a] = fx;
      g.force.y[a] = fy;
      g.force.z[a] = fz;
      g.torque.x[a] = tx;
      g.torque.y[a] = ty;
      g.torque.z[a] = tz;
    }
  });
}

void PairContact::run(World& world) {
  compute_pair_forces(world.grains, world.resources.get<NeighborList>(), world.resources.get<PairHistory>(),
                      world.resources.get<ContactTable>(), world.clock.dt, world.resources.get<PairForces>());
}

}  // namespace gf
