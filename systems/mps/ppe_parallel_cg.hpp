// The pressure Poisson equation's own solver: a Jacobi-preconditioned conjugate gradient over a compact copy
// of the couplings, run with TBB on every core.
//
// Each solve first compacts the neighbour list (which holds every pair within r_e plus the Verlet skin, many of
// them with zero weight, and rows for dummy and surface nodes) into a CSR matrix of the active rows only:
// row r is the r-th active node, its off-diagonal entries are the neighbours j that are active with
// W_ij != 0, stored as (column, W_ij); A = diag - c W as in ppe.hpp. Counting, filling and every CG pass run
// over fixed blocks of rows in parallel, and each dot product is summed per block then over the blocks in
// order, so the result does not depend on the thread count (bit for bit). The passes run on SIMD batches:
// a row's couplings kLanes at a time with hardware gathers, the vector updates kLanes rows at a time, so no
// sum is one long chain of dependent additions.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/simd.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

struct PpeProblem;
struct PpeResult;

struct CompactPpe {
  std::vector<std::int32_t> row_of;    // node -> row, -1 if inactive
  std::vector<std::uint32_t> node_of;  // row -> node
  std::vector<std::uint32_t> start;    // rows + 1 offsets into col, w
  std::vector<std::uint32_t> col;      // the neighbour's row
  std::vector<double> w;               // W_ij (the matrix entry is -c W_ij)
  // The solve's vectors, kept between solves to avoid reallocating them every step.
  std::vector<double> diag, inv, b, x, r, d, q, part1, part2;
};

// Active rows and their couplings from the neighbour list.
void ppe_compact(const NeighborPairs& nb, const PpeProblem& pb, CompactPpe& sys);

// Copies the diagonal, the right-hand side and the warm start p into the compact rows (diag, inv, b, x), zeroes p,
// sizes the solve's vectors; returns |b|. ppe_finish writes x back into p on the active nodes and completes res
// with the iterations and the relative residual reached (converged: finite and within the tolerance).
double ppe_load(CompactPpe& sys, const PpeProblem& pb, ColumnD& p);
PpeResult ppe_finish(const CompactPpe& sys, PpeResult res, int iterations, double rnorm, double bnorm,
                     double tolerance, ColumnD& p);

// Solves from the pressure in p (the last step's: a warm start), into p on active nodes.
PpeResult ppe_solve_parallel(CompactPpe& sys, const PpeProblem& pb, const PpeSettings& s, ColumnD& p);

}  // namespace gf
