// The locally averaged liquid (coupling.averaged, systems/mps/liquid_fraction.hpp): the PPE's density term
// targets eps n0 at each node (the free-surface test's part: mps_free_surface_test.cpp); in a tank over a
// fixed bed of grains the liquid makes room for them and its level rises, where the plain liquid's does not.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "systems/coupling/coupled_step.hpp"
#include "systems/mps/explicit_step.hpp"
#include "systems/mps/free_surface.hpp"
#include "systems/mps/kernel.hpp"
#include "systems/mps/liquid_fraction.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/number_density.hpp"
#include "systems/mps/ppe.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "tests/mps_support.hpp"

using namespace gf;

TEST_CASE("averaged liquid: the PPE's density term reads eps n0", "[coupled]") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("hydrostatic_2d.toml"));
  FluidNodes& f = sim.nodes();
  LiquidParams& lp = sim.params();
  NeighborPairs nb;
  test::prepare_nodes(sim, nb);
  std::vector<double> eps(f.size());
  for (std::size_t i = 0; i < f.size(); ++i) eps[i] = 0.5 + 0.5 * static_cast<double>(i % 7) / 6.0;
  const double dt = sim.scene().dt;
  PpeProblem plain, averaged;
  ppe_prepare(f, nb, lp, dt, plain);
  ppe_prepare(f, nb, lp, dt, averaged, eps);
  // b = -source with source = (1 - gamma) rho/dt div - gamma rho/dt^2 (n - target)/n0: the targets eps n0
  // and n0 differ in b by gamma rho/dt^2 (1 - eps), and nothing else changes.
  const double g = lp.gamma * lp.rho / (dt * dt);
  std::size_t rows = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!plain.active[i]) continue;
    ++rows;
    CHECK(averaged.b[i] - plain.b[i] == Approx(g * (1.0 - eps[i])).epsilon(1e-9).margin(1e-9 * g));
    CHECK(averaged.diag[i] == plain.diag[i]);
  }
  CHECK(rows > 100);
}

TEST_CASE("averaged liquid: the viscous term of thinned nodes is normalised by eps n0", "[coupled]") {
  // A cubic lattice thinned to eps = 0.7 (spacing l0 0.7^(-1/3)), the kernel of the full lattice (re =
  // 2.1 l0), and u = x^2, whose Laplacian is 2: the centre's viscous acceleration should be 2 nu. The
  // n0 form sums the thinned lattice's weights, about eps of the full lattice's: on this lattice it
  // reads 0.767 of 2 nu, and over eps (the averaged liquid's n~0 = eps n0) 1.096 of it. The lattice sums
  // are exact to round-off, so the bounds are those values to 1e-3.
  const double l0 = 0.01, eps = 0.7, spacing = l0 / std::cbrt(eps);
  FluidNodes f;
  f.dim = 3;
  std::size_t c = 0;
  for (int k = -4; k <= 4; ++k)
    for (int j = -4; j <= 4; ++j)
      for (int i = -4; i <= 4; ++i) {
        if (i == 0 && j == 0 && k == 0) c = f.size();
        f.push(kFluid, i * spacing, j * spacing, k * spacing);
      }
  LiquidParams lp;
  lp.k = lattice_constants(3, l0, 2.1 * l0);
  NeighborPairs nb;
  build_neighbors(f, lp.k.re, Periodicity{}, nb);
  compute_number_density(f, nb, lp.k.re);
  auto viscous = [&](std::span<const double> fraction) {
    for (std::size_t i = 0; i < f.size(); ++i) f.u[i] = f.x[i] * f.x[i], f.v[i] = f.w[i] = 0.0;
    predict_velocity(f, nb, lp, 1e-9, fraction);
    return f.ax[c] / (2.0 * lp.nu);
  };
  const std::vector<double> fraction(f.size(), eps);
  const double plain = viscous({}), averaged = viscous(fraction);
  CAPTURE(plain, averaged, f.n[c] / lp.k.n0);
  test::record_result("averaged_viscous.csv", "eps,n_over_n0,lap_n0_form_over_exact,lap_eps_n0_form_over_exact",
                      test::csv_number(eps, 3) + "," + test::csv_number(f.n[c] / lp.k.n0, 4) + "," +
                          test::csv_number(plain, 4) + "," + test::csv_number(averaged, 4));
  CHECK(plain == Approx(0.767).margin(1e-3));
  CHECK(averaged == Approx(1.096).margin(1e-3));
  CHECK(averaged == Approx(plain / eps).epsilon(1e-12));
}

namespace {

// A 30 mm tank of water 30 mm deep over a fixed bed of 3 mm beads, 24 % by volume in its lowest 12 mm.
// gradient: the liquid's pressure-gradient form, "sum" or "min" (liquid_params.hpp).
std::string tank_over_bed(bool averaged, const std::string& gradient) {
  return "[run]\ndt = 1.0e-3\nduration = 0.15\ngravity = [0.0, -9.81, 0.0]\nvelocity_scale = 0.5\nskin = 2.0e-4\n"
         "[liquid]\ndim = 3\nl0 = 0.002\ndensity = 1000.0\nviscosity = 1.0e-5\ngamma = 0.05\ngradient = \"" + gradient + "\"\n"
         "[geometry]\ntype = \"tank\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.05, 0.03]\n"
         "[[fluid]]\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.03, 0.03]\n"
         "[[species]]\nname = \"glass\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
         "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
         "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.03, 0.012, 0.03] }\n"
         "volume_fraction = { glass = 0.24 }\nseed = 3\n"
         "[coupling]\nfixed_grains = true\nsmoothing_radius = 0.005\nshare_with = \"fluid_nodes\"\n"
         "averaged = " + std::string(averaged ? "true" : "false") + "\n";
}

struct Level {
  double rise = 0;        // m, the mean height change of the liquid nodes that started above the bed's reach
  double grains = 0;      // m^3, the bed's volume
  double bed_ratio = 0;   // the mean n/n0 of the fluid nodes in the bed's middle 4 to 8 mm
  double bed_eps = 0;     // their mean liquid fraction
};

Level level_over_bed(bool averaged, const std::string& gradient) {
  CoupledSimulation sim = CoupledSimulation::from_text(tank_over_bed(averaged, gradient));
  World& w = sim.world();
  const FluidNodes& f = w.tables.get<FluidNodes>();
  std::vector<std::size_t> top;
  double y0 = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && f.y[i] > 0.018) top.push_back(i), y0 += f.y[i];
  sim.advance(sim.scene().steps());
  Level l;
  for (std::size_t i : top) l.rise += f.y[i];
  l.rise = (l.rise - y0) / static_cast<double>(top.size());
  for (std::size_t i = 0; i < w.grains.n_owned; ++i) l.grains += 4.0 / 3.0 * M_PI * std::pow(w.grains.radius.r[i], 3);
  const CouplingState& c = w.resources.get<CouplingState>();
  double n = 0, e = 0, count = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.kind[i] == kFluid && f.y[i] > 0.004 && f.y[i] < 0.008) n += f.n[i], e += c.node_eps[i], count += 1;
  l.bed_ratio = n / count / sim.scene().liquid.params.k.n0;
  l.bed_eps = e / count;
  return l;
}

}  // namespace

// Rise of the clear liquid over the plain liquid's (both settle alike under their weight), the bed's
// volume over the tank's section, and the levels, recorded per gradient form.
struct Displacement {
  Level plain, averaged;
  double displaced = 0, rise = 0;
};

Displacement displacement(const std::string& gradient) {
  Displacement d{level_over_bed(false, gradient), level_over_bed(true, gradient)};
  d.displaced = d.averaged.grains / (0.03 * 0.03);
  d.rise = d.averaged.rise - d.plain.rise;
  test::record_result("averaged_liquid.csv",
                      "gradient,plain_rise_m,averaged_rise_m,displaced_height_m,rise_share,bed_n_over_n0,bed_eps,plain_bed_n_over_n0",
                      gradient + "," + test::csv_number(d.plain.rise, 6) + "," + test::csv_number(d.averaged.rise, 6) + "," +
                          test::csv_number(d.displaced, 6) + "," + test::csv_number(d.rise / d.displaced, 4) + "," +
                          test::csv_number(d.averaged.bed_ratio, 4) + "," + test::csv_number(d.averaged.bed_eps, 4) + "," +
                          test::csv_number(d.plain.bed_ratio, 4));
  return d;
}

TEST_CASE("averaged liquid: a tank's level rises over a fixed bed as the liquid makes room for the grains", "[coupled]") {
  const Displacement sum = displacement("sum"), min = displacement("min");
  CAPTURE(min.rise, min.displaced, min.averaged.bed_ratio, min.averaged.bed_eps, min.plain.bed_ratio);
  CAPTURE(sum.rise, sum.averaged.bed_ratio, sum.averaged.bed_eps);
  // The bed is 24 % grains, so its nodes should thin to eps = 0.76 (the kernel reads 0.74 in its
  // middle) and the clear liquid rise by the displaced 2.87 mm. Measured with the "min" gradient: the
  // rise is 63 % of that and the nodes sit at n/n0 = 0.815 (the "sum" form: 47 %, 0.859). The bounds
  // hold that partial displacement and no overshoot: above half the displaced height, below all of it;
  // the nodes thinned, not past eps.
  CHECK(min.rise > min.displaced / 2.0);
  CHECK(min.rise < min.displaced);
  CHECK(min.averaged.bed_ratio < min.plain.bed_ratio - 0.15);
  CHECK(min.averaged.bed_ratio > min.averaged.bed_eps);
  CHECK(min.plain.bed_ratio > 0.97);  // the plain liquid fills the grains' volume at n0
  // The eps each node reads is the bed's, from the node's own volume (void_fraction.hpp): within the
  // kernel's smoothing of the bed's 0.76 (the 4-8 mm slab is 4 mm from the bed's edges, under h = 5 mm).
  CHECK(min.averaged.bed_eps == Approx(0.76).margin(0.04));
  // The "sum" gradient, (p_j + p_i), pushes nodes from dense to sparse liquid wherever the pressure is
  // high (a uniform pressure gives a force along the density gradient): it fights the thinning, and its
  // bed's nodes stay denser than the "min" form's, (p_j - p_min).
  CHECK(sum.averaged.bed_ratio > min.averaged.bed_ratio + 0.02);
}
