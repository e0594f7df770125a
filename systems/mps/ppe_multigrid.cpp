#include "systems/mps/ppe_multigrid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include <tbb/enumerable_thread_specific.h>

#include "systems/mps/ppe.hpp"
#include "systems/mps/row_blocks.hpp"

namespace gf {

namespace {

constexpr std::size_t kMostLevels = 30;

// A level's matrix as the cycle reads it: row i of A v is diag[i] v[i] + scale sum_k val[k] v[col[k]].
struct LevelMatrix {
  const std::uint32_t* start;
  const std::uint32_t* col;
  const double* val;
  double scale;
  const double* diag;
  std::size_t n;
  double row(std::size_t i, const double* v) const { return diag[i] * v[i] + scale * row_dot(start, col, val, i, v); }
};

LevelMatrix matrix_of(const CompactPpe& sys, double c, const PpeMultigrid& mg, std::size_t l) {
  if (l == 0) return {sys.start.data(), sys.col.data(), sys.w.data(), -c, sys.diag.data(), sys.node_of.size()};
  const MultigridLevel& L = mg.levels[l];
  return {L.start.data(), L.col.data(), L.val.data(), 1.0, L.diag.data(), L.rows()};
}

// The finest level's cubes: each active node's position in units of `side` from the lowest corner.
void finest_cubes(const CompactPpe& sys, const FluidNodes& f, double side, MultigridLevel& L) {
  const std::size_t m = sys.node_of.size();
  double lo[3] = {INFINITY, INFINITY, INFINITY};
  for (std::uint32_t node : sys.node_of) {
    lo[0] = std::min(lo[0], f.x[node]);
    lo[1] = std::min(lo[1], f.y[node]);
    lo[2] = std::min(lo[2], f.z[node]);
  }
  L.cx.resize(m);
  L.cy.resize(m);
  L.cz.resize(m);
  for_row_blocks(m, [&](std::size_t, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) {
      const std::uint32_t node = sys.node_of[i];
      L.cx[i] = static_cast<std::int32_t>(std::floor((f.x[node] - lo[0]) / side));
      L.cy[i] = static_cast<std::int32_t>(std::floor((f.y[node] - lo[1]) / side));
      L.cz[i] = static_cast<std::int32_t>(std::floor((f.z[node] - lo[2]) / side));
    }
  });
}

// Groups the rows of `fine` whose cubes, halved `shift` times, coincide: one row of `coarse` per group, numbered
// in order of first appearance (deterministic), with the group's cube as its coordinates.
void group_rows(MultigridLevel& fine, int shift, MultigridLevel& coarse) {
  const std::size_t n = fine.rows();
  std::int64_t nx = 1, ny = 1, nz = 1;
  for (std::size_t i = 0; i < n; ++i) {
    nx = std::max<std::int64_t>(nx, (fine.cx[i] >> shift) + 1);
    ny = std::max<std::int64_t>(ny, (fine.cy[i] >> shift) + 1);
    nz = std::max<std::int64_t>(nz, (fine.cz[i] >> shift) + 1);
  }
  const double volume = static_cast<double>(nx) * static_cast<double>(ny) * static_cast<double>(nz);
  const bool dense = volume <= 8.0 * static_cast<double>(n) + 4096.0;
  std::vector<std::int32_t> slot(dense ? static_cast<std::size_t>(volume) : 0, -1);
  std::unordered_map<std::int64_t, std::int32_t> sparse;
  coarse.cx.clear();
  coarse.cy.clear();
  coarse.cz.clear();
  fine.agg.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::int32_t x = fine.cx[i] >> shift, y = fine.cy[i] >> shift, z = fine.cz[i] >> shift;
    const std::int64_t key = x + nx * (y + ny * static_cast<std::int64_t>(z));
    std::int32_t& s = dense ? slot[static_cast<std::size_t>(key)] : sparse.try_emplace(key, -1).first->second;
    if (s < 0) {
      s = static_cast<std::int32_t>(coarse.cx.size());
      coarse.cx.push_back(x);
      coarse.cy.push_back(y);
      coarse.cz.push_back(z);
    }
    fine.agg[i] = static_cast<std::uint32_t>(s);
  }
  // The groups' members by counting sort, in row order within each group.
  const std::size_t nc = coarse.rows();
  fine.member_start.assign(nc + 1, 0);
  for (std::size_t i = 0; i < n; ++i) ++fine.member_start[fine.agg[i] + 1];
  for (std::size_t g = 0; g < nc; ++g) fine.member_start[g + 1] += fine.member_start[g];
  fine.members.resize(n);
  std::vector<std::uint32_t> next(fine.member_start.begin(), fine.member_start.end() - 1);
  for (std::size_t i = 0; i < n; ++i) fine.members[next[fine.agg[i]]++] = static_cast<std::uint32_t>(i);
}

// coarse = P^T A P: coarse row I sums the fine rows of group I, each entry into the column of its group.
void galerkin(const LevelMatrix& A, const MultigridLevel& fine, MultigridLevel& coarse) {
  const std::size_t nc = coarse.rows();
  struct Scratch {
    std::vector<std::uint64_t> tag;  // which (pass, row) last saw each coarse column
    std::vector<std::uint32_t> slot;
  };
  tbb::enumerable_thread_specific<Scratch> scratch([nc] { return Scratch{std::vector<std::uint64_t>(nc, 0), std::vector<std::uint32_t>(nc, 0)}; });
  coarse.start.assign(nc + 1, 0);
  coarse.diag.resize(nc);
  // Pass 1 (tags 1..nc): the distinct columns of each coarse row. Pass 2 (tags nc+1..2nc): fill and sum.
  for (int pass = 0; pass < 2; ++pass) {
    for_row_blocks(nc, [&](std::size_t, std::size_t g0, std::size_t g1) {
      Scratch& sc = scratch.local();
      for (std::size_t g = g0; g < g1; ++g) {
        const std::uint64_t tag = pass * nc + g + 1;
        std::uint32_t k = pass == 0 ? 0 : coarse.start[g];
        double d = 0;
        for (std::uint32_t mi = fine.member_start[g]; mi < fine.member_start[g + 1]; ++mi) {
          const std::uint32_t i = fine.members[mi];
          d += A.diag[i];
          for (std::uint32_t e = A.start[i]; e < A.start[i + 1]; ++e) {
            const std::uint32_t h = fine.agg[A.col[e]];
            const double v = A.scale * A.val[e];
            if (h == g) {
              d += v;
            } else if (sc.tag[h] != tag) {
              sc.tag[h] = tag;
              if (pass == 1) {
                sc.slot[h] = k;
                coarse.col[k] = h;
                coarse.val[k] = v;
              }
              ++k;
            } else if (pass == 1) {
              coarse.val[sc.slot[h]] += v;
            }
          }
        }
        if (pass == 0) coarse.start[g + 1] = k;
        else coarse.diag[g] = d;
      }
    });
    if (pass == 0) {
      for (std::size_t g = 0; g < nc; ++g) coarse.start[g + 1] += coarse.start[g];
      coarse.col.resize(coarse.start[nc]);
      coarse.val.resize(coarse.start[nc]);
    }
  }
}

// The last level, dense: A + (mean diagonal / n) 1 1^T when closed, whose solution for a source summing to zero
// is A's own with zero sum.
void factor_coarsest(const MultigridLevel& L, bool closed, PpeMultigrid& mg) {
  const auto n = static_cast<Eigen::Index>(L.rows());
  double mean_diag = 0;
  for (double d : L.diag) mean_diag += d / static_cast<double>(n);
  Eigen::MatrixXd D = Eigen::MatrixXd::Constant(n, n, closed ? mean_diag / static_cast<double>(n) : 0.0);
  for (Eigen::Index i = 0; i < n; ++i) {
    D(i, i) += L.diag[static_cast<std::size_t>(i)];
    for (std::uint32_t e = L.start[static_cast<std::size_t>(i)]; e < L.start[static_cast<std::size_t>(i) + 1]; ++e)
      D(i, static_cast<Eigen::Index>(L.col[e])) += L.val[e];
  }
  mg.coarsest.compute(D);
}

// r = b - A x.
void residual(const LevelMatrix& A, const double* b, const double* x, double* r) {
  for_row_blocks(A.n, [&](std::size_t, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) r[i] = b[i] - A.row(i, x);
  });
}

// One damped Jacobi sweep: x += omega D^-1 (b - A x), through r.
void jacobi(const LevelMatrix& A, const double* inv, const double* b, double* x, double* r) {
  residual(A, b, x, r);
  for_row_blocks(A.n, [&](std::size_t, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) x[i] += inv[i] * r[i];
  });
}

void cycle(const CompactPpe& sys, double c, const MultigridSettings& s, PpeMultigrid& mg, std::size_t l,
           const double* b, double* x) {
  MultigridLevel& L = mg.levels[l];
  if (l + 1 == mg.depth) {
    const auto n = static_cast<Eigen::Index>(L.rows());
    Eigen::Map<Eigen::VectorXd>(x, n) = mg.coarsest.solve(Eigen::Map<const Eigen::VectorXd>(b, n));
    return;
  }
  MultigridLevel& C = mg.levels[l + 1];
  const LevelMatrix A = matrix_of(sys, c, mg, l);
  const double* inv = L.inv.data();
  double* r = L.r.data();
  for_row_blocks(A.n, [&](std::size_t, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) x[i] = inv[i] * b[i];
  });
  for (int k = 1; k < s.sweeps; ++k) jacobi(A, inv, b, x, r);
  residual(A, b, x, r);
  for_row_blocks(C.rows(), [&](std::size_t, std::size_t g0, std::size_t g1) {
    for (std::size_t g = g0; g < g1; ++g) {
      double t = 0;
      for (std::uint32_t mi = L.member_start[g]; mi < L.member_start[g + 1]; ++mi) t += r[L.members[mi]];
      C.b[g] = t;
    }
  });
  cycle(sys, c, s, mg, l + 1, C.b.data(), C.x.data());
  if (s.cycle == 2 && l + 2 < mg.depth) {
    residual(matrix_of(sys, c, mg, l + 1), C.b.data(), C.x.data(), C.b2.data());
    cycle(sys, c, s, mg, l + 1, C.b2.data(), C.x2.data());
    for (std::size_t g = 0; g < C.rows(); ++g) C.x[g] += C.x2[g];
  }
  for_row_blocks(A.n, [&](std::size_t, std::size_t i0, std::size_t i1) {
    for (std::size_t i = i0; i < i1; ++i) x[i] += s.correction * C.x[L.agg[i]];
  });
  for (int k = 0; k < s.sweeps; ++k) jacobi(A, inv, b, x, r);
}

}  // namespace

bool multigrid_stale(const CompactPpe& sys, const MultigridSettings& s, const PpeMultigrid& mg) {
  return mg.depth == 0 || mg.solves >= s.reuse || mg.node_of != sys.node_of;
}

void multigrid_setup(const CompactPpe& sys, const PpeProblem& pb, const FluidNodes& f, double side,
                     const MultigridSettings& s, PpeMultigrid& mg) {
  if (mg.levels.empty()) mg.levels.resize(1);
  mg.node_of = sys.node_of;
  mg.solves = 0;
  ++mg.builds;
  finest_cubes(sys, f, side, mg.levels[0]);
  mg.depth = 1;
  for (;;) {
    MultigridLevel& L = mg.levels[mg.depth - 1];
    const LevelMatrix A = matrix_of(sys, pb.c, mg, mg.depth - 1);
    L.inv.resize(L.rows());
    for (std::size_t i = 0; i < L.rows(); ++i) L.inv[i] = s.omega / A.diag[i];
    L.r.resize(L.rows());
    if (L.rows() <= static_cast<std::size_t>(std::max(1, s.coarsest)) || mg.depth == kMostLevels) break;
    if (mg.levels.size() == mg.depth) mg.levels.emplace_back();
    MultigridLevel& C = mg.levels[mg.depth];
    MultigridLevel& F = mg.levels[mg.depth - 1];  // the emplace may have moved L
    group_rows(F, mg.depth == 1 ? 0 : 1, C);
    galerkin(matrix_of(sys, pb.c, mg, mg.depth - 1), F, C);
    for (auto* v : {&C.b, &C.x, &C.b2, &C.x2}) v->resize(C.rows());
    ++mg.depth;
  }
  factor_coarsest(mg.levels[mg.depth - 1], pb.closed, mg);
}

void multigrid_apply(const CompactPpe& sys, double c, const MultigridSettings& s, PpeMultigrid& mg, const double* r,
                     double* z) {
  cycle(sys, c, s, mg, 0, r, z);
}

PpeResult ppe_solve_multigrid(CompactPpe& sys, const PpeProblem& pb, const FluidNodes& f, const LiquidParams& lp,
                              PpeMultigrid& mg, ColumnD& p) {
  const std::size_t m = sys.node_of.size();
  PpeResult res;
  res.unknowns = pb.unknowns;
  res.closed = pb.closed;
  const double bnorm = ppe_load(sys, pb, p);
  if (m == 0 || bnorm == 0) return res;
  const PpeSettings& s = lp.solver;
  if (multigrid_stale(sys, s.multigrid, mg)) {
    multigrid_setup(sys, pb, f, s.multigrid.aggregate * lp.k.l0, s.multigrid, mg);
  } else {
    // The coarse levels stay; the finest level's smoother follows this step's diagonal.
    MultigridLevel& L0 = mg.levels[0];
    for_row_blocks(m, [&](std::size_t, std::size_t i0, std::size_t i1) {
      for (std::size_t i = i0; i < i1; ++i) L0.inv[i] = s.multigrid.omega / sys.diag[i];
    });
  }
  ++mg.solves;
  mg.z.resize(m);
  mg.part1.assign(row_blocks(m), 0.0);
  mg.part2.assign(row_blocks(m), 0.0);
  const LevelMatrix A = matrix_of(sys, pb.c, mg, 0);
  double *b = sys.b.data(), *x = sys.x.data(), *r = sys.r.data(), *d = sys.d.data(), *q = sys.q.data();
  double *z = mg.z.data(), *part1 = mg.part1.data(), *part2 = mg.part2.data();
  // z = M r, then r.z summed per block in order.
  auto precondition = [&] {
    multigrid_apply(sys, pb.c, s.multigrid, mg, r, z);
    for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
      double t = 0;
      for (std::size_t i = i0; i < i1; ++i) t += r[i] * z[i];
      part1[blk] = t;
    });
    return sum_in_order(mg.part1);
  };
  for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
    double t = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      r[i] = b[i] - A.row(i, x);
      t += r[i] * r[i];
    }
    part2[blk] = t;
  });
  double rnorm = std::sqrt(sum_in_order(mg.part2));
  double rz = rnorm > s.tolerance * bnorm ? precondition() : 0.0;
  std::copy(z, z + m, d);
  int it = 0;
  while (rnorm > s.tolerance * bnorm && it < s.max_iterations) {
    for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
      double t = 0;
      for (std::size_t i = i0; i < i1; ++i) {
        q[i] = A.row(i, d);
        t += d[i] * q[i];
      }
      part1[blk] = t;
    });
    const double dq = sum_in_order(mg.part1);
    if (!(dq > 0) || !(rz > 0)) break;  // loss of positive definiteness: reported as non-convergence below
    const double alpha = rz / dq;
    for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
      double t = 0;
      for (std::size_t i = i0; i < i1; ++i) {
        x[i] += alpha * d[i];
        r[i] -= alpha * q[i];
        t += r[i] * r[i];
      }
      part2[blk] = t;
    });
    rnorm = std::sqrt(sum_in_order(mg.part2));
    ++it;
    if (rnorm <= s.tolerance * bnorm) break;
    const double rz_new = precondition();
    const double beta = rz_new / rz;
    rz = rz_new;
    for_row_blocks(m, [&](std::size_t, std::size_t i0, std::size_t i1) {
      for (std::size_t i = i0; i < i1; ++i) d[i] = z[i] + beta * d[i];
    });
  }
  return ppe_finish(sys, res, it, rnorm, bnorm, s.tolerance, p);
}

}  // namespace gf
