#include "systems/mps/ppe.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "systems/mps/pair_batch.hpp"

namespace gf {

// A row's pairs kLanes at a time (pair_batch.hpp), the rest one by one; pairs at zero distance or zero weight
// add nothing (their lanes are masked before the division).
void compute_divergence(FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k) {
  const double c = k.grad_coef();
  const PairBatches pairs(f, nb);
  const BatchD zero(0.0), one(1.0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, f.size(), 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (f.kind[i] == kDummy) {
        f.div[i] = 0;
        continue;
      }
      const BatchD ui(f.u[i]), vi(f.v[i]), wi(f.w[i]);
      std::uint32_t q = nb.start[i];
      const std::uint32_t end = nb.start[i + 1];
      BatchD acc(0.0);
      for (; q + kLanes <= end; q += kLanes) {
        BatchD dx, dy, dz;
        pairs.rel(i, q, dx, dy, dz);
        const BatchD r2 = dx * dx + dy * dy + dz * dz;
        const BatchD w = BatchD::load_unaligned(nb.w.data() + q);
        const auto on = (r2 > zero) && (w != zero);
        const BatchD dot = dx * (pairs.neighbours(f.u.data(), q) - ui) + dy * (pairs.neighbours(f.v.data(), q) - vi) +
                           dz * (pairs.neighbours(f.w.data(), q) - wi);
        acc += xsimd::select(on, dot / xsimd::select(on, r2, one) * w, zero);
      }
      double s = 0;
      for (; q < end; ++q) {
        double dx, dy, dz;
        nb.rel(f, i, q, dx, dy, dz);
        const double r2 = dx * dx + dy * dy + dz * dz;
        if (r2 <= 0 || nb.w[q] == 0) continue;
        const std::uint32_t j = nb.j[q];
        s += (dx * (f.u[j] - f.u[i]) + dy * (f.v[j] - f.v[i]) + dz * (f.w[j] - f.w[i])) / r2 * nb.w[q];
      }
      f.div[i] = c * (xsimd::hadd(acc) + s);
    }
  });
}

void ppe_prepare(const FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt, PpeProblem& pb,
                 std::span<const double> eps) {
  const std::size_t n = f.size();
  pb.active.assign(n, 0);
  pb.b.assign(n, 0.0);
  pb.diag.assign(n, 0.0);
  pb.c = lp.k.lap_coef();
  const double shift = lp.rho * lp.compressibility / (dt * dt);
  const double n0 = lp.k.n0;
  for (std::size_t i = 0; i < n; ++i) pb.active[i] = f.kind[i] != kDummy && !f.surface[i];
  bool dirichlet = false;
  for (std::size_t i = 0; i < n; ++i) dirichlet |= f.kind[i] != kDummy && f.surface[i];
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 512), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) {
      if (!pb.active[i]) continue;
      double sw = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q)
        if (f.kind[nb.j[q]] != kDummy) sw += nb.w[q];
      pb.diag[i] = pb.c * sw + shift;
      const double target = eps.empty() ? n0 : eps[i] * n0;  // a locally averaged liquid's n~0 = eps n0
      const double source = (1.0 - lp.gamma) * lp.rho / dt * f.div[i] -
                            lp.gamma * lp.rho / (dt * dt) * (f.n[i] - target) / n0;
      pb.b[i] = -source;
    }
  });
  // A row without any coupling (an isolated node) cannot be solved: treat it as Dirichlet.
  std::size_t m = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (pb.active[i] && !(pb.diag[i] > 0)) {
      pb.active[i] = 0;
      pb.b[i] = 0;
      dirichlet = true;
    }
    m += pb.active[i];
  }
  pb.unknowns = m;
  pb.closed = !dirichlet && !(shift > 0);
  if (pb.closed && m > 0) {
    double mean = 0;
    for (std::size_t i = 0; i < n; ++i) mean += pb.b[i];
    mean /= static_cast<double>(m);
    for (std::size_t i = 0; i < n; ++i)
      if (pb.active[i]) pb.b[i] -= mean;
  }
}

namespace {

constexpr std::size_t kBlock = 1024;

template <class F>
void par_rows(std::size_t n, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kBlock), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) f(i);
  });
}

void remove_mean(const PpeProblem& pb, ColumnD& p) {
  double mean = 0;
  for (std::size_t i = 0; i < pb.active.size(); ++i)
    if (pb.active[i]) mean += p[i];
  mean /= static_cast<double>(std::max<std::size_t>(1, pb.unknowns));
  for (std::size_t i = 0; i < pb.active.size(); ++i)
    if (pb.active[i]) p[i] -= mean;
}

}  // namespace

void ppe_apply(const NeighborPairs& nb, const PpeProblem& pb, const std::vector<double>& x, std::vector<double>& y) {
  par_rows(pb.active.size(), [&](std::size_t i) {
    if (!pb.active[i]) {
      y[i] = 0;
      return;
    }
    double s = 0;
    for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) s += nb.w[q] * x[nb.j[q]];
    y[i] = pb.diag[i] * x[i] - pb.c * s;
  });
}

void number_rows(const PpeProblem& pb, std::vector<std::int32_t>& row_of, std::vector<std::uint32_t>& node_of) {
  const std::size_t n = pb.active.size();
  row_of.assign(n, -1);
  node_of.clear();
  for (std::size_t i = 0; i < n; ++i)
    if (pb.active[i]) {
      row_of[i] = static_cast<std::int32_t>(node_of.size());
      node_of.push_back(static_cast<std::uint32_t>(i));
    }
}

void ppe_assemble_eigen(const NeighborPairs& nb, const PpeProblem& pb, EigenPpe& sys) {
  number_rows(pb, sys.row_of, sys.node_of);
  const auto m = static_cast<Eigen::Index>(sys.node_of.size());
  // Rows are filled in order straight into compressed storage: no triplet sort.
  Eigen::SparseMatrix<double, Eigen::RowMajor>& A = sys.A;
  A.resize(m, m);
  std::vector<int> nnz(static_cast<std::size_t>(m));
  for (Eigen::Index r = 0; r < m; ++r) {
    const std::uint32_t i = sys.node_of[r];
    int c = 1;
    for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) c += sys.row_of[nb.j[q]] >= 0 && nb.w[q] != 0;
    nnz[r] = c;
  }
  A.reserve(nnz);
  for (Eigen::Index r = 0; r < m; ++r) {
    const std::uint32_t i = sys.node_of[r];
    A.insert(r, r) = pb.diag[i];
    for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) {
      const std::int32_t c = sys.row_of[nb.j[q]];
      if (c >= 0 && nb.w[q] != 0) A.insert(r, c) = -pb.c * nb.w[q];
    }
  }
  A.makeCompressed();
}

PpeResult ppe_solve_eigen(const EigenPpe& sys, const PpeProblem& pb, const PpeSettings& s, ColumnD& p) {
  using Mat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const auto m = static_cast<Eigen::Index>(sys.node_of.size());
  PpeResult res;
  res.unknowns = pb.unknowns;
  res.closed = pb.closed;
  Eigen::VectorXd b(m), x0(m), x;
  for (Eigen::Index r = 0; r < m; ++r) {
    b[r] = pb.b[sys.node_of[r]];
    x0[r] = p[sys.node_of[r]];
  }
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
  if (m == 0 || b.norm() == 0) return res;
  auto run = [&](auto& cg) {
    cg.setTolerance(s.tolerance);
    cg.setMaxIterations(s.max_iterations);
    cg.compute(sys.A);
    if (cg.info() != Eigen::Success) {
      res.converged = false;
      res.residual = INFINITY;
      return;
    }
    x = cg.solveWithGuess(b, x0);
    res.iterations = static_cast<int>(cg.iterations());
    res.residual = cg.error();
    res.converged = cg.info() == Eigen::Success && std::isfinite(cg.error()) && cg.error() <= s.tolerance;
  };
  if (s.preconditioner == Preconditioner::IncompleteCholesky) {
    Eigen::ConjugateGradient<Mat, Eigen::Lower | Eigen::Upper, Eigen::IncompleteCholesky<double>> cg;
    run(cg);
  } else {
    Eigen::ConjugateGradient<Mat, Eigen::Lower | Eigen::Upper, Eigen::DiagonalPreconditioner<double>> cg;
    run(cg);
  }
  if (x.size() == m)
    for (Eigen::Index r = 0; r < m; ++r) p[sys.node_of[r]] = x[r];
  if (pb.closed) remove_mean(pb, p);
  return res;
}

PpeResult solve_pressure(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt, PpeWorkspace& ws,
                         std::span<const double> eps) {
  compute_divergence(f, nb, lp.k);
  ppe_prepare(f, nb, lp, dt, ws.problem, eps);
  PpeResult res;
  if (lp.solver.kind == PpeSolverKind::EigenCg) {
    ppe_assemble_eigen(nb, ws.problem, ws.eigen);
    res = ppe_solve_eigen(ws.eigen, ws.problem, lp.solver, f.p);
  } else {
    ppe_compact(nb, ws.problem, ws.compact);
    res = lp.solver.preconditioner == Preconditioner::Multigrid
              ? ppe_solve_multigrid(ws.compact, ws.problem, f, lp, ws.multigrid, f.p)
              : ppe_solve_parallel(ws.compact, ws.problem, lp.solver, f.p);
    if (ws.problem.closed) remove_mean(ws.problem, f.p);
  }
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] == kDummy) continue;
    if (!ws.problem.active[i]) f.p[i] = 0;
    else if (lp.clip_negative && f.p[i] < 0) f.p[i] = 0;
  }
  return res;
}

}  // namespace gf
