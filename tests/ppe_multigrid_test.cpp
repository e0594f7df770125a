// The pressure Poisson equation's multigrid preconditioner (systems/mps/ppe_multigrid.hpp): the cycle is a
// symmetric positive definite operator (what CG needs of it), the coarse levels keep a closed domain's constant
// null space, the preconditioned CG reaches the Jacobi CG's solution in fewer iterations, open and closed, and
// its result does not depend on the thread count; a hierarchy reused over several steps is rebuilt on schedule
// and leaves the solution at the solver's tolerance.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <tbb/global_control.h>

#include "mps_support.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/ppe.hpp"

using namespace gf;

namespace {

// A 3D tank, 14^3 fluid nodes of 5 mm under a free surface (about 5,000 unknowns: three levels).
std::string tank3d() {
  return R"(
[run]
dt = 5.0e-4
duration = 0.01
velocity_scale = 1.0
gravity = [0.0, -9.81, 0.0]
[liquid]
dim = 3
l0 = 0.005
density = 1000.0
viscosity = 1.0e-6
clip_negative = false
[geometry]
type = "tank"
lo = [0.0, 0.0, 0.0]
hi = [0.07, 0.1, 0.07]
[[fluid]]
lo = [0.0, 0.0, 0.0]
hi = [0.07, 0.07, 0.07]
)";
}

// A 2D periodic channel filled completely: no free surface, the system is singular (closed).
std::string full_channel() { return test::full_channel_2d(0.3, 0.1, "clip_negative = false\n"); }

// The scene's nodes stirred by random velocities (a source with every wavelength), the PPE prepared and compacted.
struct Stirred {
  LiquidSimulation sim;
  NeighborPairs nb;
  PpeWorkspace ws;
  explicit Stirred(const std::string& text) : sim(LiquidSimulation::from_text(text)) {
    FluidNodes& f = sim.nodes();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> vel(-0.05, 0.05);
    for (std::size_t i = 0; i < f.size(); ++i)
      if (f.kind[i] == kFluid) {
        f.u[i] = vel(rng);
        f.v[i] = vel(rng);
        f.w[i] = sim.params().k.dim == 3 ? vel(rng) : 0.0;
      }
    test::prepare_nodes(sim, nb);
    compute_divergence(f, nb, sim.params().k);
    ppe_prepare(f, nb, sim.params(), sim.scene().dt, ws.problem);
    ppe_compact(nb, ws.problem, ws.compact);
    ColumnD p(f.size());
    ppe_load(ws.compact, ws.problem, p);
    const LiquidParams& lp = sim.params();
    multigrid_setup(ws.compact, ws.problem, f, lp.solver.multigrid.aggregate * lp.k.l0, lp.solver.multigrid,
                    ws.multigrid);
  }
  std::vector<double> apply(const std::vector<double>& r) {
    std::vector<double> z(r.size());
    multigrid_apply(ws.compact, ws.problem.c, sim.params().solver.multigrid, ws.multigrid, r.data(), z.data());
    return z;
  }
};

double dot(const std::vector<double>& a, const std::vector<double>& b) {
  double s = 0;
  for (std::size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// Solves with the given preconditioner from p = 0 to 1e-10; the pressure per node.
PpeResult solve_with(Stirred& s, Preconditioner pc, ColumnD& p) {
  LiquidParams lp = s.sim.params();
  lp.solver.preconditioner = pc;
  lp.solver.tolerance = 1e-10;
  FluidNodes& f = s.sim.nodes();
  for (std::size_t i = 0; i < f.size(); ++i) f.p[i] = 0;
  const PpeResult r = solve_pressure(f, s.nb, lp, s.sim.scene().dt, s.ws);
  p = f.p;
  return r;
}

}  // namespace

TEST_CASE("the multigrid cycle is symmetric and positive definite, open and closed") {
  for (const std::string& text : {tank3d(), full_channel()}) {
    Stirred s(text);
    const std::size_t m = s.ws.compact.node_of.size();
    CAPTURE(m, s.ws.multigrid.depth, s.ws.problem.closed);
    REQUIRE(s.ws.multigrid.depth >= 3);
    std::mt19937_64 rng(5);
    std::normal_distribution<double> g(0.0, 1.0);
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<double> u(m), v(m);
      for (std::size_t i = 0; i < m; ++i) {
        u[i] = g(rng);
        v[i] = g(rng);
      }
      if (s.ws.problem.closed) {
        // A closed domain's residuals sum to zero (the source is projected so): test on that subspace.
        for (auto* x : {&u, &v}) {
          double mean = 0;
          for (double e : *x) mean += e / static_cast<double>(m);
          for (double& e : *x) e -= mean;
        }
      }
      const std::vector<double> Mu = s.apply(u), Mv = s.apply(v);
      // Symmetry to round-off: every step of the cycle is a symmetric operation or mirrored by one; the sums
      // run over a few thousand terms, so 1e-12 of the products' scale leaves room for their rounding.
      const double scale = std::sqrt(dot(u, u) * dot(Mv, Mv));
      CHECK(std::abs(dot(u, Mv) - dot(v, Mu)) < 1e-12 * scale);
      CHECK(dot(v, Mv) > 0);
      CHECK(dot(u, Mu) > 0);
    }
  }
}

TEST_CASE("the coarse levels of a closed domain keep its constant null space") {
  Stirred s(full_channel());
  REQUIRE(s.ws.problem.closed);
  for (std::size_t l = 1; l < s.ws.multigrid.depth; ++l) {
    const MultigridLevel& L = s.ws.multigrid.levels[l];
    CAPTURE(l, L.rows());
    double worst = 0;
    for (std::size_t g = 0; g < L.rows(); ++g) {
      double sum = L.diag[g];
      for (std::uint32_t e = L.start[g]; e < L.start[g + 1]; ++e) sum += L.val[e];
      worst = std::max(worst, std::abs(sum) / L.diag[g]);
    }
    // Each coarse row sums fine rows that sum to zero exactly in exact arithmetic (A 1 = 0); what remains is
    // the rounding of a few hundred additions of terms of the diagonal's size.
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("the multigrid CG reaches the Jacobi CG's pressure in fewer iterations") {
  for (const std::string& text : {tank3d(), full_channel()}) {
    Stirred s(text);
    ColumnD ref, p;
    const PpeResult jac = solve_with(s, Preconditioner::Jacobi, ref);
    const PpeResult mg = solve_with(s, Preconditioner::Multigrid, p);
    CAPTURE(jac.iterations, mg.iterations, mg.residual, s.ws.problem.closed);
    REQUIRE(jac.converged);
    REQUIRE(mg.converged);
    CHECK(mg.residual <= 1e-10);
    // Measured: 3D tank 77 against 13 iterations, closed channel 106 against 17. A third leaves a margin and
    // still fails a cycle that does not act on the long wavelengths.
    CHECK(3 * mg.iterations < jac.iterations);
    // Both reach a relative residual of 1e-10. Jacobi CG's counts (about sqrt(kappa)/2 ln(2/tol) iterations)
    // put the condition number near 1e2, so each error is below about 1e-8 of |p| in the 2-norm, and below
    // 1e-6 of the largest pressure node by node for these few thousand nodes (closed: both have zero mean).
    double pmax = 0, dmax = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      pmax = std::max(pmax, std::abs(ref[i]));
      dmax = std::max(dmax, std::abs(ref[i] - p[i]));
    }
    CHECK(dmax < 1e-6 * pmax);
  }
}

TEST_CASE("the multigrid CG gives the same pressure bit for bit on one and two threads") {
  ColumnD one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    Stirred s(tank3d());
    REQUIRE(solve_with(s, Preconditioner::Multigrid, one).converged);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    Stirred s(tank3d());
    REQUIRE(solve_with(s, Preconditioner::Multigrid, two).converged);
  }
  REQUIRE(one.size() == two.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < one.size(); ++i) differ += one[i] != two[i];
  CHECK(differ == 0);
}

TEST_CASE("a multigrid hierarchy serves multigrid_reuse steps, and the pressure stays at the solver's tolerance") {
  // The 3D tank under gravity, 12 steps: its nodes settle, so each step's matrix differs from the last.
  auto with_solver = [](const std::string& solver) {
    std::string text = tank3d();
    text.replace(text.find("[geometry]"), 0, "[liquid.solver]\npreconditioner = \"multigrid\"\n" + solver + "\n");
    return text;
  };
  auto every = LiquidSimulation::from_text(with_solver("multigrid_reuse = 1"));
  auto reused = LiquidSimulation::from_text(with_solver("multigrid_reuse = 5"));
  REQUIRE(reused.params().solver.multigrid.reuse == 5);
  every.advance(12);
  reused.advance(12);
  const auto& mg = reused.world().resources.get<PpeWorkspace>().multigrid;
  CHECK(every.world().resources.get<PpeWorkspace>().multigrid.builds == 12);
  CHECK(mg.builds == 3);  // steps 1, 6 and 11
  const auto& d = reused.world().resources.get<LiquidDiagnostics>();
  CHECK(d.ppe.converged);
  CHECK(d.ppe.residual <= reused.params().solver.tolerance);
  // Both solve each step to a relative residual of 1e-8 (the pressure's error is then about 1e-6 of its largest
  // value node by node: the test above); over 12 steps these differences move the nodes by far less than the
  // pressure they set, so the two pressures agree to 1e-5 of the largest.
  const FluidNodes &a = every.nodes(), &b = reused.nodes();
  double pmax = 0, dmax = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a.kind[i] != kDummy) {
      pmax = std::max(pmax, std::abs(a.p[i]));
      dmax = std::max(dmax, std::abs(a.p[i] - b.p[i]));
    }
  CAPTURE(pmax, dmax);
  CHECK(pmax > 0);
  CHECK(dmax < 1e-5 * pmax);
  // A checkpoint written after step 12 makes step 13 rebuild, as a run resumed there must.
  multigrid_invalidate(reused.world().resources.get<PpeWorkspace>().multigrid);
  reused.advance(1);
  CHECK(mg.builds == 4);
}

TEST_CASE("multigrid_reuse is refused without the multigrid preconditioner, naming the key and the fix") {
  std::string text = tank3d();
  text.replace(text.find("[geometry]"), 0, "[liquid.solver]\nmultigrid_reuse = 4\n");
  REQUIRE_THROWS_WITH(LiquidSimulation::from_text(text),
                      Catch::Matchers::Contains("multigrid_reuse") && Catch::Matchers::Contains("preconditioner = \"multigrid\""));
}
