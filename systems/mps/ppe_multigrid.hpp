// A multigrid preconditioner for the pressure Poisson equation's parallel CG, built on the nodes' positions
// (geometric aggregation, in the spirit of Osaki, Morikawa and Asai's multigrid for particle pressure equations):
//   - level 0 is the compact system itself (ppe_parallel_cg.hpp);
//   - its unknowns are grouped by cubes of side `aggregate` l0 (about 8 nodes each in 3D at 2 l0), each cube one
//     unknown of level 1; level k's cubes are grouped by cubes of twice their side into level k + 1;
//   - each coarse matrix is the Galerkin product P^T A P with piecewise-constant P (a coarse entry is the sum of
//     the fine entries between the two groups), so every level is symmetric, keeps the constant null space of a
//     closed domain, and costs one pass over the finer level's couplings to form;
//   - the last level (at most `coarsest` unknowns) is solved by a dense Cholesky factorisation, shifted by the
//     constant vector's projector when the domain is closed (singular);
//   - one cycle: damped Jacobi sweeps, the restricted residual solved on the next level (once: V, twice: W),
//     prolonged back with a scale, the same sweeps again. Pre- and post-smoothing mirror each other, so the cycle
//     is a symmetric positive definite operator and CG may use it.
// The hierarchy serves `reuse` solves (1 by default: rebuilt every step). A hierarchy built at an earlier step
// still gives a symmetric positive definite cycle, so CG converges to the same tolerance with it; only the
// iterations grow as the nodes move away from the cubes they were grouped in. The finest level is always this
// step's matrix. The hierarchy is rebuilt when the system's rows change (another active set) and after a
// checkpoint (multigrid_invalidate), so that a resumed run builds the same one as the unbroken run.
// Every pass runs over fixed blocks of rows and sums in a fixed order (row_blocks.hpp): the result does not
// depend on the thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/simd.hpp"

#include <Eigen/Dense>

#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/liquid_params.hpp"
#include "systems/mps/ppe_parallel_cg.hpp"

namespace gf {

struct PpeProblem;
struct PpeResult;

struct MultigridLevel {
  // The level's matrix: diag plus off-diagonal entries (col, val) in compressed rows. Level 0 keeps these empty
  // and reads the compact system's (-c W) instead.
  std::vector<std::uint32_t> start, col;
  std::vector<double> val, diag;
  std::vector<double> inv;                // omega / diag
  std::vector<std::int32_t> cx, cy, cz;   // each row's cube, in units of this level's cube side
  std::vector<std::uint32_t> agg;         // row -> row of the next level
  std::vector<std::uint32_t> member_start, members;  // next level's row -> this level's rows
  std::vector<double> b, x, r, b2, x2;    // the cycle's vectors (b2, x2: a W-cycle's second visit)
  std::size_t rows() const { return cx.size(); }
};

struct PpeMultigrid {
  std::vector<MultigridLevel> levels;  // the first `depth` are in use; the rest keep their storage
  std::size_t depth = 0;
  int solves = 0;                      // solves served by the current hierarchy
  std::int64_t builds = 0;             // hierarchies built
  std::vector<std::uint32_t> node_of;  // the compact rows' nodes when it was built
  Eigen::LDLT<Eigen::MatrixXd> coarsest;
  std::vector<double> z, part1, part2;  // the CG's preconditioned residual and block sums
};

// Builds the hierarchy for the compact system `sys` (its diag and inv loaded: ppe_load) of problem pb, from the
// positions of the nodes in f. `side`: the finest cubes' side in metres.
void multigrid_setup(const CompactPpe& sys, const PpeProblem& pb, const FluidNodes& f, double side,
                     const MultigridSettings& s, PpeMultigrid& mg);

// Whether the next solve must rebuild the hierarchy: none yet, `reuse` solves served, or other rows.
bool multigrid_stale(const CompactPpe& sys, const MultigridSettings& s, const PpeMultigrid& mg);

// The next solve rebuilds the hierarchy (called where a checkpoint is written).
inline void multigrid_invalidate(PpeMultigrid& mg) { mg.depth = 0; }

// z = M r: one cycle from z = 0 (vectors over the compact rows).
void multigrid_apply(const CompactPpe& sys, double c, const MultigridSettings& s, PpeMultigrid& mg, const double* r,
                     double* z);

// CG preconditioned by the cycle, from the warm start in p, into p on active nodes.
PpeResult ppe_solve_multigrid(CompactPpe& sys, const PpeProblem& pb, const FluidNodes& f, const LiquidParams& lp,
                              PpeMultigrid& mg, ColumnD& p);

}  // namespace gf
