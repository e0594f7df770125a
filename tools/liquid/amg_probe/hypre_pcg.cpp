// Solves the pressure Poisson system written by dump_ppe with hypre's conjugate gradient preconditioned by
// BoomerAMG (one V-cycle per iteration), to the same relative residual (1e-8, two-norm) from p = 0, and
// prints one JSON object: the options, the AMG hierarchy's setup time, the solve time and iterations
// (medians over REPEATS setups and solves), and the time to hand the matrix to hypre.
//   hypre_pcg FILE.bin REPEATS COARSEN THETA INTERP AGG_LEVELS PMAX RELAX
// COARSEN: 8 PMIS, 10 HMIS; INTERP: 6 extended+i, 13 MM-extended+i; RELAX: 6 hybrid symmetric Gauss-Seidel,
// 8 l1 Gauss-Seidel, 18 l1 Jacobi. hypre's threads: OMP_NUM_THREADS.
#include <HYPRE.h>
#include <HYPRE_IJ_mv.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

template <class T>
void get(std::FILE* f, T* p, std::size_t n) {
  if (std::fread(p, sizeof(T), n, f) != n) {
    std::fprintf(stderr, "hypre_pcg: the file ends early\n");
    std::exit(1);
  }
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  if (argc != 9) {
    std::fprintf(stderr, "usage: hypre_pcg FILE.bin REPEATS COARSEN THETA INTERP AGG_LEVELS PMAX RELAX\n");
    return 2;
  }
  std::FILE* f = std::fopen(argv[1], "rb");
  if (!f) return 1;
  std::uint64_t m = 0, nnz = 0;
  double c = 0;
  get(f, &m, 1);
  get(f, &nnz, 1);
  get(f, &c, 1);
  std::vector<std::uint32_t> start(m + 1), col(nnz);
  std::vector<double> w(nnz), diag(m), b(m);
  get(f, start.data(), m + 1);
  get(f, col.data(), nnz);
  get(f, w.data(), nnz);
  get(f, diag.data(), m);
  get(f, b.data(), m);
  std::fclose(f);
  const int repeats = std::atoi(argv[2]), coarsen = std::atoi(argv[3]), interp = std::atoi(argv[5]);
  const int agg = std::atoi(argv[6]), pmax = std::atoi(argv[7]), relax = std::atoi(argv[8]);
  const double theta = std::atof(argv[4]);
  HYPRE_Init();

  // A = diag - c W, row by row with the diagonal first.
  const Clock::time_point t0 = Clock::now();
  const auto last = static_cast<HYPRE_BigInt>(m) - 1;
  HYPRE_IJMatrix A;
  HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, last, 0, last, &A);
  HYPRE_IJMatrixSetObjectType(A, HYPRE_PARCSR);
  std::vector<HYPRE_Int> ncols(m);
  for (std::size_t r = 0; r < m; ++r) ncols[r] = static_cast<HYPRE_Int>(start[r + 1] - start[r] + 1);
  HYPRE_IJMatrixSetRowSizes(A, ncols.data());
  HYPRE_IJMatrixInitialize(A);
  std::vector<HYPRE_BigInt> rows(m), cols(nnz + m);
  std::vector<double> vals(nnz + m);
  for (std::size_t r = 0, q = 0; r < m; ++r) {
    rows[r] = static_cast<HYPRE_BigInt>(r);
    cols[q] = static_cast<HYPRE_BigInt>(r);
    vals[q++] = diag[r];
    for (std::uint32_t k = start[r]; k < start[r + 1]; ++k) cols[q] = col[k], vals[q++] = -c * w[k];
  }
  HYPRE_IJMatrixSetValues(A, static_cast<HYPRE_Int>(m), ncols.data(), rows.data(), cols.data(), vals.data());
  HYPRE_IJMatrixAssemble(A);
  HYPRE_ParCSRMatrix pA;
  HYPRE_IJMatrixGetObject(A, reinterpret_cast<void**>(&pA));
  HYPRE_IJVector B, X;
  for (HYPRE_IJVector* v : {&B, &X}) {
    HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, last, v);
    HYPRE_IJVectorSetObjectType(*v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(*v);
  }
  HYPRE_IJVectorSetValues(B, static_cast<HYPRE_Int>(m), rows.data(), b.data());
  HYPRE_IJVectorAssemble(B);
  const double assemble_ms = ms_since(t0);
  HYPRE_ParVector pb, px;
  HYPRE_IJVectorGetObject(B, reinterpret_cast<void**>(&pb));

  std::vector<double> setup, solve;
  int iterations = 0;
  double residual = 0;
  const std::vector<double> zero(m, 0.0);
  for (int k = 0; k < repeats; ++k) {
    HYPRE_IJVectorSetValues(X, static_cast<HYPRE_Int>(m), rows.data(), zero.data());
    HYPRE_IJVectorAssemble(X);
    HYPRE_IJVectorGetObject(X, reinterpret_cast<void**>(&px));
    HYPRE_Solver pcg, amg;
    HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &pcg);
    HYPRE_PCGSetTol(pcg, 1e-8);
    HYPRE_PCGSetMaxIter(pcg, 1000);
    HYPRE_PCGSetTwoNorm(pcg, 1);
    HYPRE_BoomerAMGCreate(&amg);
    HYPRE_BoomerAMGSetCoarsenType(amg, coarsen);
    HYPRE_BoomerAMGSetStrongThreshold(amg, theta);
    HYPRE_BoomerAMGSetInterpType(amg, interp);
    HYPRE_BoomerAMGSetPMaxElmts(amg, pmax);
    HYPRE_BoomerAMGSetAggNumLevels(amg, agg);
    HYPRE_BoomerAMGSetRelaxType(amg, relax);
    HYPRE_BoomerAMGSetNumSweeps(amg, 1);
    HYPRE_BoomerAMGSetMaxIter(amg, 1);
    HYPRE_BoomerAMGSetTol(amg, 0.0);
    HYPRE_PCGSetPrecond(pcg, reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSolve),
                        reinterpret_cast<HYPRE_PtrToSolverFcn>(HYPRE_BoomerAMGSetup), amg);
    Clock::time_point t = Clock::now();
    HYPRE_ParCSRPCGSetup(pcg, pA, pb, px);
    setup.push_back(ms_since(t));
    t = Clock::now();
    HYPRE_ParCSRPCGSolve(pcg, pA, pb, px);
    solve.push_back(ms_since(t));
    HYPRE_PCGGetNumIterations(pcg, &iterations);
    HYPRE_PCGGetFinalRelativeResidualNorm(pcg, &residual);
    HYPRE_BoomerAMGDestroy(amg);
    HYPRE_ParCSRPCGDestroy(pcg);
  }
  const char* omp = std::getenv("OMP_NUM_THREADS");
  std::printf("{\"coarsen\": %d, \"theta\": %g, \"interp\": %d, \"agg_levels\": %d, \"pmax\": %d, \"relax\": %d, "
              "\"omp_threads\": \"%s\", \"iterations\": %d, \"residual\": %.3g, \"assemble_ms\": %.2f, "
              "\"setup_ms_median\": %.2f, \"solve_ms_median\": %.2f, \"repeats\": %d}\n",
              coarsen, theta, interp, agg, pmax, relax, omp ? omp : "", iterations, residual, assemble_ms,
              median(setup), median(solve), repeats);
  HYPRE_IJMatrixDestroy(A);
  HYPRE_IJVectorDestroy(B);
  HYPRE_IJVectorDestroy(X);
  HYPRE_Finalize();
  MPI_Finalize();
}
