// The second rung of seed 003's validation ladder: liquid driven through a fixed packed bed, against
// Ergun's pressure gradient
//   dP/L = 150 mu (1 - eps)^2 U / (eps^3 d^2) + 1.75 rho (1 - eps) U^2 / (eps^3 d).
// scenes/liquid/packed_bed.toml: 2 mm spheres held fixed (coupling.fixed_grains) on a body-centred cubic
// lattice (liquid fraction 0.394) in a 12 x 12 mm column, periodic over 12 mm along its axis x, the lattice
// running on through the no-slip walls; liquid of 1000 kg/m^3 and mu = 0.01 Pa s at l0 = 0.75 mm
// (d / l0 = 2.67), h = 1.5 d = 4 l0, dt = 0.25 ms, 200 steps from rest. A body force f along x stands
// for the driving pressure gradient (rho f is the column's dP/L); it is set to Ergun's gradient at a
// target speed and the liquid finds its own. U is the mean of eps u over the liquid nodes, u read as the
// interstitial speed (the liquid is not locally averaged: its nodes fill the bed's whole volume).
// The drag law is Ergun's own (drag.hpp), so this checks the coupling, not Ergun: the liquid fraction the
// shares give the nodes, the speed read at the grains, the reaction, and the walls. Measured (the sweep
// below, studies/seed003/results/ergun_bed.csv, Re_p 0.4 to 8; the column closed: no free-surface test, gamma 0.05, the
// "min" gradient):
//  - the core of the column (nodes 4 mm or more from the walls) meets Ergun at its own U and eps within
//    1.5 to 2.5 %; the core's eps, sampled by nodes that move through the fixed lattice, reads 0.392 to
//    0.398, and Ergun's (1 - eps)^2 / eps^3 turns 0.003 of that into 3 %: hence 8 %;
//  - over the whole column rho f lies 22-24 % below Ergun at the column's U: within h of a wall a grain reads
//    the liquid's speed over the wall's nodes too, which do not move, so it takes less drag and the
//    liquid channels along the walls (a limit of the kernel at walls, not of the bed); checked only as
//    channelling (the column's U above the core's);
//  - the grains take 98.8-99.0 % of rho f, the walls' shear the rest (checked within 3 %);
//  - the nodes' mean eps is the lattice's within 0.1 % (checked within 0.3 %).
// Not covered: above Re_p 8 the corners' jets grow (the CFL limit broken 8 ms in at Re_p 30).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "systems/coupling/coupled_step.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kD = 2.0e-3, kRho = 1000.0, kMu = 0.01;
constexpr double kSide = 0.012;          // m, the column's width along y and z and its periodic length
constexpr double kVolume = kSide * kSide * kSide;
constexpr double kCore = 0.004;          // m: the core's nodes are this far from the walls or further
constexpr double kLatticeEps = 0.39401;  // 1 - 2 (pi/6) d^3 / a^3, a = 2.4 mm
constexpr int kSamples = 4, kEvery = 10; // the last 40 steps, sampled every 10

double ergun(double u_sup, double eps) {
  const double e3 = eps * eps * eps;
  return 150.0 * kMu * (1 - eps) * (1 - eps) * u_sup / (e3 * kD * kD) + 1.75 * kRho * (1 - eps) * u_sup * u_sup / (e3 * kD);
}

// Means over a set of liquid nodes.
struct Bed {
  double eps = 0;    // liquid fraction
  double u = 0;      // m/s, speed along x
  double u_sup = 0;  // m/s, eps u along x: the superficial speed
  void add(const Bed& b, double weight) {
    eps += weight * b.eps;
    u += weight * b.u;
    u_sup += weight * b.u_sup;
  }
};

// Whether node i is at least `margin` (m) from the column's walls at y, z = 0 and kSide.
bool in_core(const gf::FluidNodes& f, std::size_t i, double margin) {
  return std::min({f.y[i], f.z[i], kSide - f.y[i], kSide - f.z[i]}) >= margin;
}

// Means over the liquid nodes at least `margin` from the walls (0: all of them).
Bed measure(gf::World& w, double margin) {
  const gf::FluidNodes& f = w.tables.get<gf::FluidNodes>();
  const std::vector<double>& eps = w.resources.get<gf::CouplingState>().node_eps;
  Bed b;
  double n = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (f.kind[i] != gf::kFluid || !in_core(f, i, margin)) continue;
    b.add({eps[i], f.u[i], eps[i] * f.u[i]}, 1.0);
    n += 1;
  }
  Bed mean;
  mean.add(b, 1.0 / n);
  return mean;
}

struct Result {
  double target = 0, drive = 0;  // m/s, Pa/m: the target U and rho f
  Bed core, column;              // means over the last 40 steps
  double drag = 0;               // Pa/m, the drag the liquid gave the grains per bed volume, same steps
  double u_start = 0;            // m/s, the column's mean speed 40 steps before the end
  double ergun_core() const { return ergun(core.u_sup, core.eps); }
  double ergun_column() const { return ergun(column.u_sup, column.eps); }
};

// Rest to steady flow under rho f = Ergun's gradient at `target` (m/s) for the lattice's eps.
Result run_case(double target) {
  const std::string force = std::to_string(ergun(target, kLatticeEps) / kRho);
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_file(
      std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/liquid/packed_bed.toml", {"run.body_force=[" + force + ", 0, 0]"});
  Result r;
  r.target = target;
  r.drive = kRho * sim.scene().liquid.params.body_force[0];
  sim.advance(sim.scene().steps() - kSamples * kEvery);
  r.u_start = measure(sim.world(), 0.0).u;
  const double dt = sim.scene().liquid.dt;
  for (int k = 0; k < kSamples; ++k) {
    sim.advance(kEvery);
    r.core.add(measure(sim.world(), kCore), 1.0 / kSamples);
    r.column.add(measure(sim.world(), 0.0), 1.0 / kSamples);
    r.drag += -sim.world().resources.get<gf::CouplingState>().fluid_reaction.x / (dt * kVolume) / kSamples;
  }
  return r;
}

std::string csv_row(const Result& r) {
  using gf::test::csv_number;
  return csv_number(r.target, 4) + "," + csv_number(kRho * r.core.u_sup * kD / kMu, 4) + "," + csv_number(r.core.eps, 5) +
         "," + csv_number(r.core.u_sup, 5) + "," + csv_number(r.drive, 6) + "," + csv_number(r.ergun_core(), 6) + "," +
         csv_number(100 * (r.drive / r.ergun_core() - 1), 3) + "," + csv_number(r.column.eps, 5) + "," +
         csv_number(r.column.u_sup, 5) + "," + csv_number(r.ergun_column(), 6) + "," +
         csv_number(100 * (r.drive / r.ergun_column() - 1), 3) + "," + csv_number(r.drag, 6) + "," +
         csv_number(100 * (1 - r.drag / r.drive), 3);
}

void check_case(const Result& r) {
  const double err_core = r.drive / r.ergun_core() - 1, err_column = r.drive / r.ergun_column() - 1;
  INFO("target U " << r.target << " m/s, rho f " << r.drive << " Pa/m; core: U " << r.core.u_sup << " m/s, eps "
                   << r.core.eps << ", Ergun " << r.ergun_core() << " Pa/m (" << 100 * err_core << " %); column: U "
                   << r.column.u_sup << " m/s, eps " << r.column.eps << ", Ergun " << r.ergun_column() << " Pa/m ("
                   << 100 * err_column << " %); drag on the grains " << r.drag << " Pa/m; column speed "
                   << r.column.u << " m/s, 40 steps before the end " << r.u_start);
  gf::test::record_result("ergun_bed.csv",
                          "U_target,Re_p,eps_core,U_core,dPdL_drive,dPdL_ergun_core,error_core_pct,eps_column,U_column,"
                          "dPdL_ergun_column,error_column_pct,dPdL_drag,wall_share_pct",
                          csv_row(r));
  CHECK(std::abs(r.column.u / r.u_start - 1) < 1.5e-2);        // steady within 1.5 % over the last 40 steps
  CHECK(r.column.eps == Approx(kLatticeEps).epsilon(3e-3));    // the nodes see the lattice's liquid fraction
  CHECK(std::abs(err_core) < 0.08);                            // the core meets Ergun
  CHECK(r.drag / r.drive > 0.97);                              // the grains take rho f but the walls' shear
  CHECK(r.drag / r.drive < 1.0);
  CHECK(r.column.u_sup > r.core.u_sup);                        // the liquid channels along the walls
}

}  // namespace

TEST_CASE("coupled: liquid through a fixed packed bed meets Ergun's pressure gradient", "[coupled][packed_bed]") {
  for (const double target : {0.005, 0.02}) check_case(run_case(target));
}

// The sweep of studies/seed003/results/ergun_bed.csv (not run by ctest): from the repository root,
//   GRAINFLOW_RESULTS=studies/seed003/results build-ergun/tests/coupled_packed_bed_test "[packed_bed_sweep]"
TEST_CASE("coupled: packed bed sweep over Re_p 0.4 to 8", "[.][packed_bed_sweep]") {
  for (const double target : {0.002, 0.005, 0.01, 0.02, 0.04}) check_case(run_case(target));
}

TEST_CASE("coupled: fixed grains stay put and give the liquid the reaction of its force", "[coupled][packed_bed]") {
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_file(std::string(GRAINFLOW_SOURCE_DIR) +
                                                               "/scenes/liquid/packed_bed.toml");
  REQUIRE(sim.scene().coupling.fixed_grains);
  CHECK(sim.scene().coupling.substeps == 1);  // the contact law sets no limit on grains that do not move
  CHECK(sim.dem_substeps().inner().describe().find("liquid_force") != std::string::npos);
  CHECK(sim.dem_substeps().inner().describe().find("integrate") == std::string::npos);
  gf::Grains& g = sim.world().grains;
  const std::vector<double> x0(g.pos.x.begin(), g.pos.x.begin() + static_cast<std::ptrdiff_t>(g.n_owned));
  sim.advance(3);
  const gf::CouplingState& c = sim.world().resources.get<gf::CouplingState>();
  CHECK(std::equal(x0.begin(), x0.end(), g.pos.x.begin()));
  CHECK(g.vel.x[0] == 0.0);
  CHECK(c.grain_impulse.x > 0.0);  // the liquid pushes the bed along the flow
  CHECK(std::abs(c.grain_impulse.x + c.reaction_impulse.x) < 1e-12 * c.grain_impulse.x);
}
