// Pressure Poisson equation of the semi-implicit step (seed 003) with Tanaka & Masunaga's mixed source:
//   <lap p>_i - rho alpha / dt^2 p_i = (1 - gamma) rho/dt <div u*>_i - gamma rho/dt^2 (n*_i - n0)/n0
// on every fluid and wall node that is not on the free surface; surface nodes hold p = 0 (Dirichlet) and dummy
// nodes are not in the system. With the MPS Laplacian, row i reads
//   A p = b,  A_ii = c sum_j W_ij + rho alpha/dt^2,  A_ij = -c W_ij,  b_i = -source_i,  c = 2d/(n0 lambda),
// the sums over fluid and wall neighbours (j on the surface contributes p_j = 0). A is symmetric and, with at
// least one Dirichlet neighbour or alpha > 0, positive definite. Sign: a compressed region (n* > n0, div u* < 0)
// has b > 0 and gets positive pressure.
//
// Closed domains (no free surface, alpha = 0, e.g. a full periodic channel) make A singular with the constant
// vector as its null space. Then b is projected to zero mean (the consistent part of the source) and the mean of
// p is removed after the solve: the pressure is defined up to that constant, and only its gradient moves fluid.
//
// Two solvers: Eigen's ConjugateGradient on an assembled sparse matrix (Jacobi or incomplete-Cholesky
// preconditioner, one thread), and a CG of our own over a compact copy of the couplings, in parallel with TBB and
// with deterministic reductions, preconditioned by Jacobi (ppe_parallel_cg.hpp) or by a multigrid cycle
// (ppe_multigrid.hpp). Both start from the previous pressure.
#pragma once

#include <span>

#include <cstddef>
#include <cstdint>
#include <vector>

// engine/simd.hpp first: it includes the AVX-512 intrinsics with GCC bug 105593's false warning silenced, and
// Eigen's vectorised kernels would otherwise include them unguarded.
#include "engine/simd.hpp"

#include <Eigen/SparseCore>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/ppe_multigrid.hpp"
#include "systems/mps/ppe_parallel_cg.hpp"

namespace gf {

struct PpeProblem {
  std::vector<std::uint8_t> active;  // per node: row of the system
  std::vector<double> b, diag;       // per node (0 where inactive)
  double c = 0;                      // 2d/(n0 lambda)
  std::size_t unknowns = 0;
  bool closed = false;               // singular: no Dirichlet node and alpha = 0
};

struct PpeResult {
  int iterations = 0;
  double residual = 0;  // relative residual reached
  bool converged = true;
  std::size_t unknowns = 0;
  bool closed = false;
};

// Divergence of the predicted velocity into f.div (wall and dummy velocities are zero).
void compute_divergence(FluidNodes& f, const NeighborPairs& nb, const MpsConstants& k);

// Builds the source, the active set and the diagonal.
// `eps`: the nodes' liquid fractions of a locally averaged liquid (liquid_fraction.hpp), empty for eps = 1.
void ppe_prepare(const FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt, PpeProblem& pb,
                 std::span<const double> eps = {});

// The system's rows: node -> row (-1 where inactive) and row -> node, rows in node order.
void number_rows(const PpeProblem& pb, std::vector<std::int32_t>& row_of, std::vector<std::uint32_t>& node_of);

struct EigenPpe {
  Eigen::SparseMatrix<double, Eigen::RowMajor> A;
  std::vector<std::int32_t> row_of;   // node -> row, -1 if inactive
  std::vector<std::uint32_t> node_of;  // row -> node
};
void ppe_assemble_eigen(const NeighborPairs& nb, const PpeProblem& pb, EigenPpe& sys);
PpeResult ppe_solve_eigen(const EigenPpe& sys, const PpeProblem& pb, const PpeSettings& s, ColumnD& p);

// y = A x over node-indexed vectors (x zero on inactive nodes), applied from the neighbour list; exposed for tests.
void ppe_apply(const NeighborPairs& nb, const PpeProblem& pb, const std::vector<double>& x, std::vector<double>& y);

// Source, solve (the scene's solver), clipping: p on fluid and wall nodes. Dummy pressures are left to
// extrapolate_dummy_pressure. Non-convergence is returned in the result, never hidden: the caller stops the run.
struct PpeWorkspace {
  PpeProblem problem;
  EigenPpe eigen;
  CompactPpe compact;
  PpeMultigrid multigrid;
};
PpeResult solve_pressure(FluidNodes& f, const NeighborPairs& nb, const LiquidParams& lp, double dt, PpeWorkspace& ws,
                         std::span<const double> eps = {});

}  // namespace gf
