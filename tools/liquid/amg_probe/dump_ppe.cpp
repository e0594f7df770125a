// Writes the pressure Poisson system of a running 3D still tank (bench/mps_tank.hpp) to a binary file, and
// times grainflow's own solver (Jacobi CG over the compact couplings, systems/mps/ppe_parallel_cg.hpp) on it
// from p = 0 at 1 and 2 threads: the reference the hypre probe (hypre_pcg.cpp) is compared with.
//   dump_ppe SIDE OUT.bin REPEATS     prints one JSON object
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <vector>

#include "bench/mps_tank.hpp"
#include "systems/mps/ppe.hpp"

namespace {

template <class T>
void put(std::FILE* f, const T* p, std::size_t n) {
  if (std::fwrite(p, sizeof(T), n, f) != n) throw std::runtime_error("dump_ppe: write failed");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: dump_ppe SIDE OUT.bin REPEATS\n");
    return 2;
  }
  const int side = std::atoi(argv[1]), repeats = std::atoi(argv[3]);
  auto sim = gf::bench::liquid_tank(3, side);
  gf::PpeWorkspace ws;
  const auto& nb = sim->world().resources.get<gf::NeighborPairs>();
  gf::ppe_prepare(sim->nodes(), nb, sim->params(), sim->scene().dt, ws.problem);
  gf::ppe_compact(nb, ws.problem, ws.compact);
  const gf::CompactPpe& c = ws.compact;
  const std::uint64_t m = c.node_of.size(), nnz = c.col.size();
  std::vector<double> diag(m), b(m);
  for (std::size_t r = 0; r < m; ++r) diag[r] = ws.problem.diag[c.node_of[r]], b[r] = ws.problem.b[c.node_of[r]];
  std::FILE* f = std::fopen(argv[2], "wb");
  if (!f) return 1;
  put(f, &m, 1);
  put(f, &nnz, 1);
  put(f, &ws.problem.c, 1);
  put(f, c.start.data(), m + 1);
  put(f, c.col.data(), nnz);
  put(f, c.w.data(), nnz);
  put(f, diag.data(), m);
  put(f, b.data(), m);
  std::fclose(f);
  std::printf("{\"rows\": %llu, \"off_diagonal\": %llu, \"closed\": %s", static_cast<unsigned long long>(m),
              static_cast<unsigned long long>(nnz), ws.problem.closed ? "true" : "false");
  for (int threads : {1, 2}) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    std::vector<double> t;
    int iterations = 0;
    double residual = 0;
    for (int k = 0; k < repeats; ++k) {
      gf::ColumnD p(sim->nodes().size());
      const auto t0 = std::chrono::steady_clock::now();
      const gf::PpeResult res = gf::ppe_solve_parallel(ws.compact, ws.problem, sim->params().solver, p);
      t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
      iterations = res.iterations;
      residual = res.residual;
    }
    std::sort(t.begin(), t.end());
    std::printf(", \"jacobi_cg_%dt\": {\"iterations\": %d, \"residual\": %.3g, \"solve_ms_median\": %.2f, \"solve_ms_min\": %.2f, \"solve_ms_max\": %.2f}",
                threads, iterations, residual, t[t.size() / 2], t.front(), t.back());
  }
  std::printf("}\n");
}
