#include "systems/integrate/integrate.hpp"

#include "engine/simd.hpp"

#include "systems/stability/stability_report.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <stdexcept>

namespace gf {

namespace {

struct IntegratorReads {
  using Reads = gf::Reads<Mass, Gravity>;
  using Writes = gf::Writes<>;
};
struct PositionWrites {
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<Position, Velocity, AngularVelocity>;
};
struct VelocityWrites {
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<Velocity, AngularVelocity>;
};

// The columns of every term, resolved for this pass (rows move at rebuilds, so never cached).
struct TermColumns {
  std::size_t nf = 0, nt = 0;
  Vec3Columns f[kMaxForceTerms], t[kMaxForceTerms];
};

TermColumns resolve(Grains& g, const ForceTerms& terms) {
  if (terms.list.size() > kMaxForceTerms) throw std::logic_error("more force terms than the integrator sums");
  TermColumns c;
  for (const ForceTerm& term : terms.list) {
    c.f[c.nf++] = term.force_columns(g);
    if (term.has_torque && g.spin) c.t[c.nt++] = term.torque_columns(g);
  }
  return c;
}

// Sum of one coordinate of every term at row (or batch) i, in declared order. N >= 0: the count is
// known at compile time (the loop unrolls; the usual pair + wall step), N < 0: n terms.
template <class T, int N, class Load>
[[gnu::always_inline]] inline T sum_terms(const Vec3Columns* cols, std::size_t n, const double* Vec3Columns::*axis,
                                          std::size_t i, Load load) {
  const std::size_t count = N >= 0 ? static_cast<std::size_t>(N) : n;
  if (count == 0) return T(0.0);
  T s = load(cols[0].*axis, i);
  for (std::size_t k = 1; k < count; ++k) s += load(cols[k].*axis, i);
  return s;
}

// One pass over the owned rows: v += h a, w += h alpha and, with Drift, x += dt v. Whole batches
// with vector loads (the columns are separate arrays, which the compiler cannot prove, so it would
// not vectorise the plain loop), the last partial batch row by row; padding rows are not touched.
// With Twice a kick of h0 (a deferred closing kick) comes first, with the same forces: the
// velocities are exactly those of two passes, the columns are read once.
// Returns whether what it wrote is finite: with Drift the positions (a non-finite velocity makes a
// non-finite position), else the velocities and spins, so each step checks all three once (with
// Twice, which holds a closing kick, the spins too). s - s is 0 for a finite sum s of them and NaN
// otherwise, and a NaN stays in the running sum (a few additions per batch, on values already in
// registers).
// Spin: the table has spin columns (Grains::spin); without them only translation is integrated.
// NF: the number of force terms when known at compile time (each with a torque when Spin), else -1.
template <bool Drift, bool Twice, bool Spin, int NF>
bool kick_rows(Grains& g, const TermColumns& tc, const Gravity& grav, double h0, double h, double dt) {
  static_assert(Drift || !Twice, "two kicks only before a drift");
  constexpr bool CheckSpin = !Drift || Twice;
  constexpr int NT = NF < 0 ? -1 : (Spin ? NF : 0);
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const std::size_t n = g.n_owned, full = n / L;
  const double gx = h * grav.x, gy = h * grav.y, gz = h * grav.z;
  const double gx0 = h0 * grav.x, gy0 = h0 * grav.y, gz0 = h0 * grav.z;
  const Vec3Columns* F = tc.f;
  const Vec3Columns* T = tc.t;
  auto one = [](const double* c, std::size_t i) { return c[i]; };
  auto row = [&](std::size_t i) {
    double bad = 0.0;
    const double fx = sum_terms<double, NF>(F, tc.nf, &Vec3Columns::x, i, one);
    const double fy = sum_terms<double, NF>(F, tc.nf, &Vec3Columns::y, i, one);
    const double fz = sum_terms<double, NF>(F, tc.nf, &Vec3Columns::z, i, one);
    const double kh[2] = {h0, h}, kgx[2] = {gx0, gx}, kgy[2] = {gy0, gy}, kgz[2] = {gz0, gz};
    for (int q = Twice ? 0 : 1; q < 2; ++q) {
      const double a = kh[q] * g.mass.inv_m[i];
      g.vel.x[i] += a * fx + kgx[q];
      g.vel.y[i] += a * fy + kgy[q];
      g.vel.z[i] += a * fz + kgz[q];
    }
    if constexpr (Spin) {
      const double tx = sum_terms<double, NT>(T, tc.nt, &Vec3Columns::x, i, one);
      const double ty = sum_terms<double, NT>(T, tc.nt, &Vec3Columns::y, i, one);
      const double tz = sum_terms<double, NT>(T, tc.nt, &Vec3Columns::z, i, one);
      for (int q = Twice ? 0 : 1; q < 2; ++q) {
        const double b = kh[q] * g.mass.inv_inertia[i];
        g.omega.x[i] += b * tx;
        g.omega.y[i] += b * ty;
        g.omega.z[i] += b * tz;
      }
      const double s = g.omega.x[i] + g.omega.y[i] + g.omega.z[i];
      if constexpr (CheckSpin) bad += s - s;
    }
    if constexpr (Drift) {
      g.pos.x[i] += dt * g.vel.x[i];
      g.pos.y[i] += dt * g.vel.y[i];
      g.pos.z[i] += dt * g.vel.z[i];
      const double s = g.pos.x[i] + g.pos.y[i] + g.pos.z[i];
      bad += s - s;
    } else {
      const double s = g.vel.x[i] + g.vel.y[i] + g.vel.z[i];
      bad += s - s;
    }
    return bad == 0.0;
  };
  auto batches = [&](const tbb::blocked_range<std::size_t>& r, bool finite) {
    const B bdt(dt);
    // The kicks of this pass: the deferred one (q = 0, with Twice), then its own (q = 1).
    const B kh[2] = {B(h0), B(h)}, kgx[2] = {B(gx0), B(gx)}, kgy[2] = {B(gy0), B(gy)}, kgz[2] = {B(gz0), B(gz)};
    B bad(0.0);
    auto ld = [](const ColumnD& c, std::size_t i) { return B::load_aligned(&c[i]); };
    auto lp = [](const double* c, std::size_t i) { return B::load_aligned(c + i); };
    for (std::size_t bt = r.begin(); bt != r.end(); ++bt) {
      const std::size_t i = bt * L;
      const B fx = sum_terms<B, NF>(F, tc.nf, &Vec3Columns::x, i, lp);
      const B fy = sum_terms<B, NF>(F, tc.nf, &Vec3Columns::y, i, lp);
      const B fz = sum_terms<B, NF>(F, tc.nf, &Vec3Columns::z, i, lp);
      B vx = ld(g.vel.x, i), vy = ld(g.vel.y, i), vz = ld(g.vel.z, i);
      for (int q = Twice ? 0 : 1; q < 2; ++q) {
        const B a = kh[q] * ld(g.mass.inv_m, i);
        vx = vx + (a * fx + kgx[q]);
        vy = vy + (a * fy + kgy[q]);
        vz = vz + (a * fz + kgz[q]);
      }
      vx.store_aligned(&g.vel.x[i]);
      vy.store_aligned(&g.vel.y[i]);
      vz.store_aligned(&g.vel.z[i]);
      if constexpr (Spin) {
        const B tx = sum_terms<B, NT>(T, tc.nt, &Vec3Columns::x, i, lp);
        const B ty = sum_terms<B, NT>(T, tc.nt, &Vec3Columns::y, i, lp);
        const B tz = sum_terms<B, NT>(T, tc.nt, &Vec3Columns::z, i, lp);
        B wx = ld(g.omega.x, i), wy = ld(g.omega.y, i), wz = ld(g.omega.z, i);
        for (int q = Twice ? 0 : 1; q < 2; ++q) {
          const B b = kh[q] * ld(g.mass.inv_inertia, i);
          wx = wx + b * tx;
          wy = wy + b * ty;
          wz = wz + b * tz;
        }
        wx.store_aligned(&g.omega.x[i]);
        wy.store_aligned(&g.omega.y[i]);
        wz.store_aligned(&g.omega.z[i]);
        if constexpr (CheckSpin) {
          const B s = (wx + wy) + wz;
          bad += s - s;
        }
      }
      if constexpr (!Drift) {
        const B s = (vx + vy) + vz;
        bad += s - s;
      }
      if constexpr (Drift) {
        const B px = ld(g.pos.x, i) + bdt * vx, py = ld(g.pos.y, i) + bdt * vy, pz = ld(g.pos.z, i) + bdt * vz;
        px.store_aligned(&g.pos.x[i]);
        py.store_aligned(&g.pos.y[i]);
        pz.store_aligned(&g.pos.z[i]);
        const B s = (px + py) + pz;
        bad += s - s;
      }
    }
    return finite && xsimd::all(bad == B(0.0));
  };
  bool finite = tbb::parallel_reduce(tbb::blocked_range<std::size_t>(0, full, 512), true, batches,
                                     [](bool a, bool b) { return a && b; });
  for (std::size_t i = full * L; i < n; ++i) finite = row(i) && finite;
  return finite;
}

}  // namespace

namespace {

// The pass for the table's rotation and the terms' count: one or two terms (each with a torque when
// the grains rotate) are compiled with their count, any other list through the general loop.
template <bool Drift, bool Twice, bool Spin>
bool kick_pass(Grains& g, const ForceTerms& terms, const Gravity& grav, double h0, double h, double dt) {
  const TermColumns tc = resolve(g, terms);
  const std::size_t torques_each = Spin ? 1 : 0;
  if (tc.nf == 2 && tc.nt == 2 * torques_each) return kick_rows<Drift, Twice, Spin, 2>(g, tc, grav, h0, h, dt);
  if (tc.nf == 1 && tc.nt == torques_each) return kick_rows<Drift, Twice, Spin, 1>(g, tc, grav, h0, h, dt);
  return kick_rows<Drift, Twice, Spin, -1>(g, tc, grav, h0, h, dt);
}

}  // namespace

bool kick(Grains& g, const ForceTerms& terms, const Gravity& grav, double h) {
  return g.spin ? kick_pass<false, false, true>(g, terms, grav, 0.0, h, 0.0)
                : kick_pass<false, false, false>(g, terms, grav, 0.0, h, 0.0);
}

bool kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double h, double dt) {
  return g.spin ? kick_pass<true, false, true>(g, terms, grav, 0.0, h, dt)
                : kick_pass<true, false, false>(g, terms, grav, 0.0, h, dt);
}

bool kick_kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double h0, double h, double dt) {
  return g.spin ? kick_pass<true, true, true>(g, terms, grav, h0, h, dt)
                : kick_pass<true, true, false>(g, terms, grav, h0, h, dt);
}

Access integrator_access(const ForceTerms& terms, Access writes) {
  Access a = access_of<IntegratorReads>();
  a.writes = std::move(writes.writes);
  for (const ForceTerm& t : terms.list) {
    a.reads.push_back(t.force);
    if (t.has_torque) a.reads.push_back(t.torque);
  }
  return a;
}

Access IntegratePositions::access() const {
  return integrator_access(terms_, access_of<PositionWrites>());
}

Access IntegrateVelocities::access() const {
  return integrator_access(terms_, access_of<VelocityWrites>());
}

void IntegratePositions::run(World& world, const StepContext& step) {
  if (step.prime) {
    // A priming pass recomputes the forces the pending kick was to use.
    if (deferred_ && deferred_->pending) throw std::logic_error("a priming pass with a closing kick pending");
    return;
  }
  const Gravity& grav = world.resources.get<Gravity>();
  if (deferred_ && deferred_->pending) {
    deferred_->pending = false;
    const double h0 = 0.5 * deferred_->step.dt;
    if (!kick_kick_drift(world.grains, terms_, grav, h0, 0.5 * step.dt, step.dt))
      report_nonfinite(world.grains, step, "the closing half-kick of the step before and this step's opening half-kick "
                                           "and drift (one pass)");
    return;
  }
  if (!kick_drift(world.grains, terms_, grav, 0.5 * step.dt, step.dt))
    report_nonfinite(world.grains, step, "the opening half-kick and drift");
}

void IntegrateVelocities::run(World& world, const StepContext& step) {
  if (step.prime) return;
  if (deferred_ && !step.observed) {
    deferred_->pending = true;
    deferred_->step = step;
    return;
  }
  if (!kick(world.grains, terms_, world.resources.get<Gravity>(), 0.5 * step.dt))
    report_nonfinite(world.grains, step, "the closing half-kick");
}

void IntegrateVelocities::complete(World& world) {
  if (!deferred_ || !deferred_->pending) return;
  deferred_->pending = false;
  if (!kick(world.grains, terms_, world.resources.get<Gravity>(), 0.5 * deferred_->step.dt))
    report_nonfinite(world.grains, deferred_->step, "the closing half-kick");
}

}  // namespace gf
