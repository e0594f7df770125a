#include "systems/periodic/periodic_images.hpp"

#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace gf {

namespace {

ColumnD* axis_column(Position& p, int d) { return d == 0 ? &p.x : (d == 1 ? &p.y : &p.z); }

}  // namespace

void wrap_positions(Grains& g, const PeriodicBox& box) {
  for (int d = 0; d < 3; ++d) {
    if (!box.on[d]) continue;
    double* x = axis_column(g.pos, d)->data();
    const double lo = box.lo[d], len = box.length(d);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, g.n_owned, 8192), [&](const tbb::blocked_range<std::size_t>& r) {
      for (std::size_t i = r.begin(); i != r.end(); ++i) {
        if (x[i] >= lo && x[i] < lo + len) continue;
        x[i] -= std::floor((x[i] - lo) / len) * len;
        // Round-off may leave a coordinate just below lo + len exactly on it: the next image below.
        if (x[i] >= lo + len) x[i] -= len;
        if (x[i] < lo) x[i] = lo;
      }
    });
  }
}

void make_images(Grains& g, PeriodicImages& im, double reach) {
  g.set_ghosts(0);
  im.owner.clear();
  im.sx.clear();
  im.sy.clear();
  im.sz.clear();
  const PeriodicBox& box = im.box;
  if (!box.any()) return;
  const std::vector<std::array<int, 3>> shifts = periodic_shifts(box, true);
  const double* p[3] = {g.pos.x.data(), g.pos.y.data(), g.pos.z.data()};
  // In row order, each row's shifts in a fixed order: the image rows depend on the positions alone.
  for (std::size_t i = 0; i < g.n_owned; ++i)
    for (const auto& s : shifts) {
      bool near = true;
      for (int d = 0; d < 3 && near; ++d) {
        if (s[d] == 0) continue;
        const double x = p[d][i] + s[d] * box.length(d);
        near = x < box.hi[d] + reach && x >= box.lo[d] - reach;
      }
      if (!near) continue;
      const std::array<double, 3> by = shift_metres(box, s);
      im.owner.push_back(static_cast<std::uint32_t>(i));
      im.sx.push_back(by[0]);
      im.sy.push_back(by[1]);
      im.sz.push_back(by[2]);
    }
  const std::size_t n0 = g.n_owned;
  g.set_ghosts(im.size());
  for (std::size_t k = 0; k < im.size(); ++k) {
    const std::size_t o = im.owner[k], r = n0 + k;
    g.radius.r[r] = g.radius.r[o];
    g.mass.m[r] = g.mass.m[o];
    g.mass.inv_m[r] = g.mass.inv_m[o];
    g.mass.inv_inertia[r] = g.mass.inv_inertia[o];
    g.species.type[r] = g.species.type[o];
    g.pid.id[r] = g.pid.id[o];
  }
  refresh_images(g, im);
}

void refresh_images(Grains& g, const PeriodicImages& im) {
  const std::size_t n0 = g.n_owned;
  for (std::size_t k = 0; k < im.size(); ++k) {
    const std::size_t o = im.owner[k], r = n0 + k;
    g.pos.x[r] = g.pos.x[o] + im.sx[k];
    g.pos.y[r] = g.pos.y[o] + im.sy[k];
    g.pos.z[r] = g.pos.z[o] + im.sz[k];
    g.vel.x[r] = g.vel.x[o];
    g.vel.y[r] = g.vel.y[o];
    g.vel.z[r] = g.vel.z[o];
    if (!g.spin) continue;
    g.omega.x[r] = g.omega.x[o];
    g.omega.y[r] = g.omega.y[o];
    g.omega.z[r] = g.omega.z[o];
  }
}

void fold_image_forces(Grains& g, const PeriodicImages& im) {
  const std::size_t n0 = g.n_owned;
  for (std::size_t k = 0; k < im.size(); ++k) {
    const std::size_t o = im.owner[k], r = n0 + k;
    g.force.x[o] += g.force.x[r];
    g.force.y[o] += g.force.y[r];
    g.force.z[o] += g.force.z[r];
    if (!g.spin) continue;
    g.torque.x[o] += g.torque.x[r];
    g.torque.y[o] += g.torque.y[r];
    g.torque.z[o] += g.torque.z[r];
  }
}

void PeriodicRefresh::run(World& world, const StepContext&) {
  refresh_images(world.grains, world.resources.get<PeriodicImages>());
}

void PeriodicFold::run(World& world, const StepContext&) {
  fold_image_forces(world.grains, world.resources.get<PeriodicImages>());
}

}  // namespace gf
