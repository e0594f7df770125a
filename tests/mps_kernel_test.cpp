// The MPS kernel and operator models (systems/mps/kernel.hpp) on square and cubic lattices: n0 and lambda
// against sums over the lattice's shells written out by hand, and the gradient, divergence and Laplacian models
// against the exact derivatives of linear and quadratic fields. On a full lattice these models are exact for
// those fields (the lattice's second moment is isotropic), so the tolerances are round-off only.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>

#include "systems/mps/explicit_step.hpp"
#include "systems/mps/kernel.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/number_density.hpp"
#include "systems/mps/ppe.hpp"
#include "systems/mps/pressure_gradient.hpp"
#include "mps_support.hpp"

using namespace gf;

namespace {

double W(double r, double re) { return re / (0.85 * r + 0.15 * re) - 1.0; }

// |ours / exact - 1|, or |ours| where the exact value is 0.
double deviation(double ours, double exact) { return exact == 0 ? std::abs(ours) : std::abs(ours / exact - 1); }

// Records, for the README's validation table, the largest deviation of a lattice check from its exact value.
void record_operator(const std::string& case_name, const std::string& quantity, const std::string& reference,
                     double worst, const std::string& bound) {
  test::LiquidFigure f;
  f.quantity = quantity;
  f.unit = "relative";
  f.reference_name = reference;
  f.measured = worst;
  f.bound = bound;
  test::record_liquid("mps_kernel_test", case_name, f, test::LiquidCost{});
}

// A (2m+1)^d block of fluid nodes of spacing l0 centred on the origin; returns the centre row.
std::size_t lattice_block(FluidNodes& f, int dim, int m, double l0) {
  f.dim = dim;
  std::size_t centre = 0;
  const int mz = dim == 3 ? m : 0;
  for (int k = -mz; k <= mz; ++k)
    for (int j = -m; j <= m; ++j)
      for (int i = -m; i <= m; ++i) {
        if (i == 0 && j == 0 && k == 0) centre = f.size();
        f.push(kFluid, i * l0, j * l0, k * l0);
      }
  return centre;
}

}  // namespace

TEST_CASE("n0 and lambda of the Zhang kernel on a square lattice, re = 2.1 l0, match the hand sum over shells") {
  const double l0 = 0.01, re = 2.1;  // re in units of l0
  // Shells within 2.1 l0 of a square-lattice node: 4 at l0, 4 at sqrt(2) l0, 4 at 2 l0 (sqrt(5) l0 > 2.1 l0).
  const double w1 = W(1, re), w2 = W(std::sqrt(2.0), re), w4 = W(2, re);
  const double n0 = 4 * (w1 + w2 + w4);
  const double lambda = 4 * (w1 * 1 + w2 * 2 + w4 * 4) / n0 * l0 * l0;
  const MpsConstants c = lattice_constants(2, l0, re * l0);
  record_operator("operators: n0 and lambda, square lattice, re = 2.1 l0", "largest |ours/exact - 1| of n0, lambda",
                  "hand sum over the lattice's shells", std::max(deviation(c.n0, n0), deviation(c.lambda, lambda)),
                  "each < 1e-13");
  // Same sums in another order: agreement to round-off.
  CHECK(c.n0 == Approx(n0).epsilon(1e-13));
  CHECK(c.lambda == Approx(lambda).epsilon(1e-13));
  // Hand values: W(l0) = 2.1/1.165 - 1 = 0.8025751, W(sqrt2 l0) = 0.3842367, W(2 l0) = 0.0421836 (7 digits).
  CHECK(c.n0 == Approx(4 * (0.8025751 + 0.3842367 + 0.0421836)).epsilon(1e-6));
}

TEST_CASE("n0 and lambda on a cubic lattice, re = 2.1 l0, match the hand sum over shells") {
  const double l0 = 0.02, re = 2.1;
  // Shells: 6 at l0, 12 at sqrt2 l0, 8 at sqrt3 l0, 6 at 2 l0.
  const double n0 = 6 * W(1, re) + 12 * W(std::sqrt(2.0), re) + 8 * W(std::sqrt(3.0), re) + 6 * W(2, re);
  const double m2 = 6 * W(1, re) * 1 + 12 * W(std::sqrt(2.0), re) * 2 + 8 * W(std::sqrt(3.0), re) * 3 + 6 * W(2, re) * 4;
  const MpsConstants c = lattice_constants(3, l0, re * l0);
  record_operator("operators: n0 and lambda, cubic lattice, re = 2.1 l0", "largest |ours/exact - 1| of n0, lambda",
                  "hand sum over the lattice's shells",
                  std::max(deviation(c.n0, n0), deviation(c.lambda, m2 / n0 * l0 * l0)), "each < 1e-13");
  CHECK(c.n0 == Approx(n0).epsilon(1e-13));
  CHECK(c.lambda == Approx(m2 / n0 * l0 * l0).epsilon(1e-13));
}

TEST_CASE("the kernel is zero at and beyond re and finite at r = 0") {
  CHECK(zhang_weight(0.021, 0.021) == 0.0);
  CHECK(zhang_weight(0.05, 0.021) == 0.0);
  CHECK(zhang_weight(0.0, 0.021) == Approx(1.0 / 0.15 - 1.0));
}

TEST_CASE("gradient, divergence and Laplacian models are exact for linear and quadratic fields on a full lattice") {
  for (int dim : {2, 3}) {
    CAPTURE(dim);
    double worst = 0;  // over both kernel radii, both gradient forms and every component
    const double l0 = 0.01;
    FluidNodes f;
    const std::size_t c = lattice_block(f, dim, 4, l0);  // 4 shells: the centre sees a full 2.1 l0 (or 3.1 l0) support
    for (double re : {2.1, 3.1}) {
      CAPTURE(re);
      const MpsConstants k = lattice_constants(dim, l0, re * l0);
      NeighborPairs nb;
      build_neighbors(f, k.re, Periodicity{}, nb);
      compute_number_density(f, nb, k.re);
      CHECK(f.n[c] == Approx(k.n0).epsilon(1e-12));  // the centre's support is the full lattice

      // Linear field phi = 3 + 2x - 5y + 7z: gradient (2, -5, 7) (z part only in 3D).
      ColumnD phi(f.size()), gx(f.size()), gy(f.size()), gz(f.size()), lap(f.size());
      for (std::size_t i = 0; i < f.size(); ++i) phi[i] = 3 + 2 * f.x[i] - 5 * f.y[i] + 7 * f.z[i];
      for (GradientForm form : {GradientForm::Sum, GradientForm::MinPressure}) {
        mps_gradient(f, nb, k, form, phi, gx, gy, gz);
        worst = std::max({worst, deviation(gx[c], 2), deviation(gy[c], -5), deviation(gz[c], dim == 3 ? 7 : 0)});
        CHECK(gx[c] == Approx(2).epsilon(1e-10));
        CHECK(gy[c] == Approx(-5).epsilon(1e-10));
        CHECK(gz[c] == Approx(dim == 3 ? 7 : 0).margin(1e-10));
      }
      // Quadratic field phi = x^2 + 2 y^2 + 3 z^2: Laplacian 2 + 4 (+ 6 in 3D).
      for (std::size_t i = 0; i < f.size(); ++i) phi[i] = f.x[i] * f.x[i] + 2 * f.y[i] * f.y[i] + 3 * f.z[i] * f.z[i];
      mps_laplacian(f, nb, k, phi, lap);
      worst = std::max(worst, deviation(lap[c], dim == 3 ? 12.0 : 6.0));
      CHECK(lap[c] == Approx(dim == 3 ? 12.0 : 6.0).epsilon(1e-10));
      // Linear velocity u = (x + 2y, 3x - 4y, z): divergence 1 - 4 (+ 1 in 3D).
      for (std::size_t i = 0; i < f.size(); ++i) {
        f.u[i] = f.x[i] + 2 * f.y[i];
        f.v[i] = 3 * f.x[i] - 4 * f.y[i];
        f.w[i] = dim == 3 ? f.z[i] : 0.0;
      }
      compute_divergence(f, nb, k);
      worst = std::max(worst, deviation(f.div[c], dim == 3 ? -2.0 : -3.0));
      CHECK(f.div[c] == Approx(dim == 3 ? -2.0 : -3.0).epsilon(1e-10));
    }
    record_operator(std::string("operators: gradient, Laplacian, divergence, ") + (dim == 3 ? "3D" : "2D") +
                        ", re = 2.1 and 3.1 l0",
                    "largest |ours/exact - 1| (|ours| where exact is 0) at the centre node",
                    "exact derivatives of linear and quadratic fields", worst, "each < 1e-10");
  }
}

TEST_CASE("the neighbour list equals brute force, with a periodic axis, after random displacements") {
  const double l0 = 0.01;
  FluidNodes f;
  f.dim = 2;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> jitter(-0.3 * l0, 0.3 * l0);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) f.push(kFluid, (i + 0.5) * l0 + jitter(rng), (j + 0.5) * l0 + jitter(rng), 0.0);
  Periodicity per{0, 0.0, 16 * l0};
  wrap_periodic(f, per);
  const double radius = 2.6 * l0;
  NeighborPairs nb;
  build_neighbors(f, radius, per, nb);
  std::size_t brute = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t q = 0; q < f.size(); ++q) {
      if (q == i) continue;
      double dx = f.x[q] - f.x[i];
      dx -= per.period() * std::round(dx / per.period());  // minimum image
      const double dy = f.y[q] - f.y[i];
      if (dx * dx + dy * dy < radius * radius) {
        ++brute;
        bool found = false;
        for (std::uint32_t k = nb.start[i]; k < nb.start[i + 1]; ++k)
          if (nb.j[k] == q) {
            double rx, ry, rz;
            nb.rel(f, i, k, rx, ry, rz);
            found = std::abs(rx - dx) < 1e-12 && std::abs(ry - dy) < 1e-12;
          }
        CHECK(found);
      }
    }
  CHECK(nb.pairs() == brute);
}
