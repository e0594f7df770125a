#include "systems/mps/ppe_parallel_cg.hpp"

#include <algorithm>
#include <cmath>

#include "engine/simd.hpp"
#include "systems/mps/ppe.hpp"
#include "systems/mps/row_blocks.hpp"

namespace gf {

void ppe_compact(const NeighborPairs& nb, const PpeProblem& pb, CompactPpe& sys) {
  number_rows(pb, sys.row_of, sys.node_of);
  const std::size_t m = sys.node_of.size();
  sys.start.assign(m + 1, 0);
  auto coupled = [&](std::uint32_t q) { return nb.w[q] != 0 && sys.row_of[nb.j[q]] >= 0; };
  for_row_blocks(m, [&](std::size_t, std::size_t r0, std::size_t r1) {
    for (std::size_t r = r0; r < r1; ++r) {
      const std::uint32_t i = sys.node_of[r];
      std::uint32_t c = 0;
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q) c += coupled(q);
      sys.start[r + 1] = c;
    }
  });
  for (std::size_t r = 0; r < m; ++r) sys.start[r + 1] += sys.start[r];
  sys.col.resize(sys.start[m]);
  sys.w.resize(sys.start[m]);
  for_row_blocks(m, [&](std::size_t, std::size_t r0, std::size_t r1) {
    for (std::size_t r = r0; r < r1; ++r) {
      const std::uint32_t i = sys.node_of[r];
      std::uint32_t k = sys.start[r];
      for (std::uint32_t q = nb.start[i]; q < nb.start[i + 1]; ++q)
        if (coupled(q)) {
          sys.col[k] = static_cast<std::uint32_t>(sys.row_of[nb.j[q]]);
          sys.w[k++] = nb.w[q];
        }
    }
  });
}

double ppe_load(CompactPpe& sys, const PpeProblem& pb, ColumnD& p) {
  const std::size_t m = sys.node_of.size();
  for (auto* v : {&sys.diag, &sys.inv, &sys.b, &sys.x, &sys.r, &sys.d, &sys.q}) v->resize(m);
  sys.part1.assign(row_blocks(m), 0.0);
  sys.part2.assign(row_blocks(m), 0.0);
  for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
    double bb = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      const std::uint32_t node = sys.node_of[i];
      sys.diag[i] = pb.diag[node];
      sys.inv[i] = 1.0 / sys.diag[i];
      sys.b[i] = pb.b[node];
      sys.x[i] = p[node];
      bb += sys.b[i] * sys.b[i];
    }
    sys.part1[blk] = bb;
  });
  for (std::size_t i = 0; i < p.size(); ++i) p[i] = 0;
  return std::sqrt(sum_in_order(sys.part1));
}

PpeResult ppe_finish(const CompactPpe& sys, PpeResult res, int iterations, double rnorm, double bnorm,
                     double tolerance, ColumnD& p) {
  res.iterations = iterations;
  res.residual = rnorm / bnorm;
  res.converged = std::isfinite(rnorm) && rnorm <= tolerance * bnorm;
  for (std::size_t i = 0; i < sys.node_of.size(); ++i) p[sys.node_of[i]] = sys.x[i];
  return res;
}

PpeResult ppe_solve_parallel(CompactPpe& sys, const PpeProblem& pb, const PpeSettings& s, ColumnD& p) {
  const std::size_t m = sys.node_of.size();
  PpeResult res;
  res.unknowns = pb.unknowns;
  res.closed = pb.closed;
  const double bnorm = ppe_load(sys, pb, p);
  if (m == 0 || bnorm == 0) return res;
  double *diag = sys.diag.data(), *inv = sys.inv.data(), *b = sys.b.data(), *x = sys.x.data();
  double *r = sys.r.data(), *d = sys.d.data(), *q = sys.q.data(), *part1 = sys.part1.data(), *part2 = sys.part2.data();
  const std::uint32_t* start = sys.start.data();
  const std::uint32_t* col = sys.col.data();
  const double* w = sys.w.data();
  const double c = pb.c;
  auto apply_row = [&](std::size_t i, const double* v) { return diag[i] * v[i] - c * row_dot(start, col, w, i, v); };
  // r = b - A x, d = z = r / diag.
  for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
    double rz = 0, rr = 0;
    for (std::size_t i = i0; i < i1; ++i) {
      r[i] = b[i] - apply_row(i, x);
      d[i] = r[i] * inv[i];
      rz += r[i] * d[i];
      rr += r[i] * r[i];
    }
    part1[blk] = rz;
    part2[blk] = rr;
  });
  double rz = sum_in_order(sys.part1);
  double rnorm = std::sqrt(sum_in_order(sys.part2));
  int it = 0;
  // Three passes an iteration: q = A d with d.q; x, r updated with r.z and r.r; d = z + beta d.
  while (rnorm > s.tolerance * bnorm && it < s.max_iterations) {
    for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
      double dq = 0;
      for (std::size_t i = i0; i < i1; ++i) {
        q[i] = apply_row(i, d);
        dq += d[i] * q[i];
      }
      part1[blk] = dq;
    });
    const double dq = sum_in_order(sys.part1);
    if (!(dq > 0)) break;  // loss of positive definiteness: reported as non-convergence below
    const double alpha = rz / dq;
    for_row_blocks(m, [&](std::size_t blk, std::size_t i0, std::size_t i1) {
      // kLanes rows at a time with one partial sum per lane (blocks start at multiples of kLanes), the block's
      // last rows one by one: a fixed order, whatever the thread count.
      BatchD rz_v(0.0), rr_v(0.0);
      std::size_t i = i0;
      for (; i + kLanes <= i1; i += kLanes) {
        (BatchD::load_unaligned(x + i) + BatchD(alpha) * BatchD::load_unaligned(d + i)).store_unaligned(x + i);
        const BatchD ri = BatchD::load_unaligned(r + i) - BatchD(alpha) * BatchD::load_unaligned(q + i);
        ri.store_unaligned(r + i);
        rz_v += ri * ri * BatchD::load_unaligned(inv + i);
        rr_v += ri * ri;
      }
      double rz_b = xsimd::hadd(rz_v), rr_b = xsimd::hadd(rr_v);
      for (; i < i1; ++i) {
        x[i] += alpha * d[i];
        r[i] -= alpha * q[i];
        rz_b += r[i] * r[i] * inv[i];
        rr_b += r[i] * r[i];
      }
      part1[blk] = rz_b;
      part2[blk] = rr_b;
    });
    const double rz_new = sum_in_order(sys.part1);
    rnorm = std::sqrt(sum_in_order(sys.part2));
    const double beta = rz_new / rz;
    rz = rz_new;
    for_row_blocks(m, [&](std::size_t, std::size_t i0, std::size_t i1) {
      for (std::size_t i = i0; i < i1; ++i) d[i] = r[i] * inv[i] + beta * d[i];
    });
    ++it;
  }
  return ppe_finish(sys, res, it, rnorm, bnorm, s.tolerance, p);
}

}  // namespace gf
