#include "systems/integrate/integrate.hpp"

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
// Returns whether what it wrote is finite: with Drift the positions (a non-finite velocity makes a
// non-finite position), else the velocities and spins, so each step checks all three once. s - s is
// 0 for a finite sum s of them and NaN otherwise, and a NaN stays in the running sum (a few
// additions per batch, on values already in registers).
// Spin: the table has spin columns (Grains::spin); without them only translation is integrated.
// NF: the number of force terms when known at compile time (each with a torque when Spin), else -1.
template <bool Drift, bool Spin, int NF>
bool kick_rows(Grains& g, const TermColumns& tc, const Gravity& grav, double h, double dt) {
  constexpr int NT = NF < 0 ? -1 : (Spin ? NF : 0);
  using B = BatchD;
  constexpr std::size_t L = kLanes;
  const std::size_t n = g.n_owned, full = n / L;
  const double gx = h * grav.x, gy = h * grav.y, gz = h * grav.z;
  const Vec3Columns* F = tc.f;
  const Vec3Columns* T = tc.t;
  auto one = [](const double* c, std::size_t i) { return c[i]; };
  auto row = [&](std::size_t i) {
    const double a = h * g.mass.inv_m[i];
    double bad = 0.0;
    g.vel.x[i] += a * sum_terms<double, NF>(F, tc.nf, &Vec3Columns::x, i, one) + gx;
    g.vel.y[i] += a * sum_terms<double, NF>(F, tc.nf, &Vec3Columns::y, i, one) + gy;
    g.vel.z[i] += a * sum_terms<double, NF>(F, tc.nf, &Vec3Columns::z, i, one) + gz;
    if constexpr (Spin) {
      const double b = h * g.mass.inv_inertia[i];
      g.omega.x[i] += b * sum_terms<double, NT>(T, tc.nt, &Vec3Columns::x, i, one);
      g.omega.y[i] += b * sum_terms<double, NT>(T, tc.nt, &Vec3Columns::y, i, one);
      g.omega.z[i] += b * sum_terms<double, NT>(T, tc.nt, &Vec3Columns::z, i, one);
      const double s = g.omega.x[i] + g.omega.y[i] + g.omega.z[i];
      if constexpr (!Drift) bad += s - s;
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
    const B bh(h), bgx(gx), bgy(gy), bgz(gz), bdt(dt);
    B bad(0.0);
    auto ld = [](const ColumnD& c, std::size_t i) { return B::load_aligned(&c[i]); };
    auto lp = [](const double* c, std::size_t i) { return B::load_aligned(c + i); };
    for (std::size_t bt = r.begin(); bt != r.end(); ++bt) {
      const std::size_t i = bt * L;
      const B a = bh * ld(g.mass.inv_m, i);
      const B vx = ld(g.vel.x, i) + (a * sum_terms<B, NF>(F, tc.nf, &Vec3Columns::x, i, lp) + bgx);
      const B vy = ld(g.vel.y, i) + (a * sum_terms<B, NF>(F, tc.nf, &Vec3Columns::y, i, lp) + bgy);
      const B vz = ld(g.vel.z, i) + (a * sum_terms<B, NF>(F, tc.nf, &Vec3Columns::z, i, lp) + bgz);
      vx.store_aligned(&g.vel.x[i]);
      vy.store_aligned(&g.vel.y[i]);
      vz.store_aligned(&g.vel.z[i]);
      if constexpr (Spin) {
        const B b = bh * ld(g.mass.inv_inertia, i);
        const B wx = ld(g.omega.x, i) + b * sum_terms<B, NT>(T, tc.nt, &Vec3Columns::x, i, lp);
        const B wy = ld(g.omega.y, i) + b * sum_terms<B, NT>(T, tc.nt, &Vec3Columns::y, i, lp);
        const B wz = ld(g.omega.z, i) + b * sum_terms<B, NT>(T, tc.nt, &Vec3Columns::z, i, lp);
        wx.store_aligned(&g.omega.x[i]);
        wy.store_aligned(&g.omega.y[i]);
        wz.store_aligned(&g.omega.z[i]);
        if constexpr (!Drift) {
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
template <bool Drift, bool Spin>
bool kick_pass(Grains& g, const ForceTerms& terms, const Gravity& grav, double h, double dt) {
  const TermColumns tc = resolve(g, terms);
  const std::size_t torques_each = Spin ? 1 : 0;
  if (tc.nf == 2 && tc.nt == 2 * torques_each) return kick_rows<Drift, Spin, 2>(g, tc, grav, h, dt);
  if (tc.nf == 1 && tc.nt == torques_each) return kick_rows<Drift, Spin, 1>(g, tc, grav, h, dt);
  return kick_rows<Drift, Spin, -1>(g, tc, grav, h, dt);
}

}  // namespace

bool kick(Grains& g, const ForceTerms& terms, const Gravity& grav, double h) {
  return g.spin ? kick_pass<false, true>(g, terms, grav, h, 0.0) : kick_pass<false, false>(g, terms, grav, h, 0.0);
}

bool kick_drift(Grains& g, const ForceTerms& terms, const Gravity& grav, double h, double dt) {
  return g.spin ? kick_pass<true, true>(g, terms, grav, h, dt) : kick_pass<true, false>(g, terms, grav, h, dt);
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
  if (step.prime) return;
  if (!kick_drift(world.grains, terms_, world.resources.get<Gravity>(), 0.5 * step.dt, step.dt))
    report_nonfinite(world.grains, step, "the opening half-kick and drift");
}

void IntegrateVelocities::run(World& world, const StepContext& step) {
  if (step.prime) return;
  if (!kick(world.grains, terms_, world.resources.get<Gravity>(), 0.5 * step.dt))
    report_nonfinite(world.grains, step, "the closing half-kick");
}

}  // namespace gf
