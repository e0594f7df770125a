#include "systems/walls/wall_contact.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/linear_spring_dashpot.hpp"

namespace gf {

namespace {

void prepare(Grains& g, Walls& walls, WallHistory& h, double t_contact) {
  walls.place(t_contact);
  if (h.cols.size() != 6 * walls.list.size() || h.active.size() != walls.list.size())
    h.shape(walls.list.size(), g.n);
}

// Per-type law constants as columns, so a batch gathers its lanes' values by type. Fixed size
// (scenes have at most kMaxSpecies species): built on the stack each call, no allocation.
struct CoeffColumns {
  alignas(64) double kn[kMaxSpecies], kt[kMaxSpecies], kr[kMaxSpecies], eta_n[kMaxSpecies], eta_t[kMaxSpecies],
      eta_r[kMaxSpecies], fs[kMaxSpecies], fr[kMaxSpecies];
  explicit CoeffColumns(const ContactTable& table) {
    for (std::size_t a = 0; a < table.types(); ++a) {
      const PairCoeffs& c = table.wall(a);
      kn[a] = c.kn;
      kt[a] = c.kt;
      kr[a] = c.kr;
      eta_n[a] = c.eta_n;
      eta_t[a] = c.eta_t;
      eta_r[a] = c.eta_r;
      fs[a] = c.fs;
      fr[a] = c.fr;
    }
  }
};

}  // namespace

void compute_wall_forces_scalar(Grains& g, Walls& walls, WallHistory& h, const ContactTable& table, double dt,
                                double t_contact) {
  prepare(g, walls, h, t_contact);
  const std::size_t nw = walls.list.size();
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
          h.active[w][i] = 0.0;
          continue;
        }
        h.active[w][i] = 1.0;
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

// The same arithmetic over batches of rows: each wall's gap is computed for every lane, and the law
// runs only for batches with a lane touching that wall now or at the last evaluation (whose springs
// must be reset); elsewhere the springs are already zero and nothing is read or written.
void compute_wall_forces(Grains& g, Walls& walls, WallHistory& h, const ContactTable& table, double dt,
                         double t_contact) {
  prepare(g, walls, h, t_contact);
  using B = BatchD;
  using V = V3<B>;
  constexpr std::size_t L = kLanes;
  const std::size_t nw = walls.list.size();
  const CoeffColumns cc(table);
  const std::size_t nown = g.n_owned;
  const std::size_t nbatch = (nown + L - 1) / L;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nbatch, 128), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t b = r.begin(); b != r.end(); ++b) {
      const std::size_t i = b * L;
      // Padding lanes past the last owned row take no part.
      alignas(64) double lane_ok[L];
      for (std::size_t l = 0; l < L; ++l) lane_ok[l] = i + l < nown ? 1.0 : 0.0;
      const auto valid = B::load_aligned(lane_ok) != B(0.0);
      const V p{B::load_aligned(&g.pos.x[i]), B::load_aligned(&g.pos.y[i]), B::load_aligned(&g.pos.z[i])};
      const B ri = B::load_aligned(&g.radius.r[i]);
      V f{B(0.0), B(0.0), B(0.0)}, t{B(0.0), B(0.0), B(0.0)};
      bool types_loaded = false;
      LsdCoeffs<B> c{};
      for (std::size_t w = 0; w < nw; ++w) {
        const Wall& wall = walls.list[w];
        V n;
        B gap;
        if (wall.kind == Wall::Kind::Plane) {
          const V pn{B(wall.cur_normal.x), B(wall.cur_normal.y), B(wall.cur_normal.z)};
          const V pp{B(wall.cur_point.x), B(wall.cur_point.y), B(wall.cur_point.z)};
          gap = dot(p - pp, pn);
          n = -pn;
        } else {
          const V ax{B(wall.cur_axis.x), B(wall.cur_axis.y), B(wall.cur_axis.z)};
          const V q = p - V{B(wall.cur_center.x), B(wall.cur_center.y), B(wall.cur_center.z)};
          const V radial = q - dot(q, ax) * ax;
          const B rho = xsimd::sqrt(dot(radial, radial));
          // A lane on the axis is far from the surface (gap = R > r for any grain that fits).
          const B inv = B(1.0) / xsimd::select(rho > B(0.0), rho, B(1.0));
          n = inv * radial;
          gap = B(wall.radius) - rho;
        }
        const auto touching = (gap < ri) && valid;
        ColumnD& act = h.active[w];
        const B was = B::load_aligned(&act[i]);
        if (!xsimd::any(touching) && !xsimd::any(was != B(0.0))) continue;
        if (!types_loaded) {
          // Padding lanes read the type column's padding (zero), a valid species.
          const std::int32_t* ti = &g.species.type[i];
          c = {gather32(cc.kn, ti),    gather32(cc.kt, ti),    gather32(cc.kr, ti), gather32(cc.eta_n, ti),
               gather32(cc.eta_t, ti), gather32(cc.eta_r, ti), gather32(cc.fs, ti), gather32(cc.fr, ti)};
          types_loaded = true;
        }
        const B delta = ri - gap;
        const B li = ri - B(0.5) * delta;
        const V wi{B::load_aligned(&g.omega.x[i]), B::load_aligned(&g.omega.y[i]), B::load_aligned(&g.omega.z[i])};
        const V vi{B::load_aligned(&g.vel.x[i]), B::load_aligned(&g.vel.y[i]), B::load_aligned(&g.vel.z[i])};
        const V contact = p + li * n;
        const double om = walls.rotation_enabled ? wall.omega : 0.0;
        const V wall_w{B(om * wall.rot_axis.x), B(om * wall.rot_axis.y), B(om * wall.rot_axis.z)};
        const V wall_v = cross(wall_w, contact - V{B(wall.rot_point.x), B(wall.rot_point.y), B(wall.rot_point.z)});
        const V v = vi + cross(li * wi, n) - wall_v;
        ColumnD* hc = &h.cols[6 * w];
        LsdState<B> s{{B::load_aligned(&hc[0][i]), B::load_aligned(&hc[1][i]), B::load_aligned(&hc[2][i])},
                      {B::load_aligned(&hc[3][i]), B::load_aligned(&hc[4][i]), B::load_aligned(&hc[5][i])}};
        const LsdResult<B> res = LinearSpringDashpot::evaluate(touching, n, delta, v, wi - wall_w, c, B(dt), s);
        s.shear.x.store_aligned(&hc[0][i]);
        s.shear.y.store_aligned(&hc[1][i]);
        s.shear.z.store_aligned(&hc[2][i]);
        s.roll.x.store_aligned(&hc[3][i]);
        s.roll.y.store_aligned(&hc[4][i]);
        s.roll.z.store_aligned(&hc[5][i]);
        xsimd::select(touching, B(1.0), B(0.0)).store_aligned(&act[i]);
        f = f + res.force;
        t = t + li * cross(n, res.force_t) + res.rolling_torque;
      }
      f.x.store_aligned(&g.wall_force.x[i]);
      f.y.store_aligned(&g.wall_force.y[i]);
      f.z.store_aligned(&g.wall_force.z[i]);
      t.x.store_aligned(&g.wall_torque.x[i]);
      t.y.store_aligned(&g.wall_torque.y[i]);
      t.z.store_aligned(&g.wall_torque.z[i]);
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
