// Dam break, 2D, Koshizuka-Oka geometry (scenes/liquid/dam_break_2d.toml), short version: the surge front up to
// T = t sqrt(2 g/a) = 2.4 against the experiments. The full run (to the far wall, finer l0) and the 3D version
// are in tests/validation/mps_dam_break_validation_test.cpp.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "mps_support.hpp"
#include "mps_support_dam.hpp"

using namespace gf;

TEST_CASE("2D dam break, l0 = a/20: surge front within 20 % of the Koshizuka-Oka experiment up to T = 2.4") {
  const double a = 0.146, g = 9.81;
  auto sim = LiquidSimulation::from_file(test::liquid_scene("dam_break_2d.toml"));
  const double t_end = 2.4 / std::sqrt(2 * g / a);
  const test::Samples s = test::run_and_sample(sim, std::llround(t_end / sim.scene().dt));
  std::vector<double> T, Z;
  const std::size_t c = test::column_index("surge_front");
  for (const auto& r : s.rows) {
    T.push_back(r[0] * std::sqrt(2 * g / a));
    Z.push_back(r[c] / a);
  }
  // At t = 0 the front is the column's face.
  CHECK(Z.front() == Approx(1.0).epsilon(1e-12));
  double sum = 0;
  int n = 0;
  for (const auto& p : test::front_experiments()) {
    if (p.source != "koshizuka_oka_1996" || p.T > 2.4 || p.T == 0) continue;
    const double ours = test::interpolate(T, Z, p.T);
    CAPTURE(p.T, p.Z, ours);
    // 20 %: at this resolution MPS leads the experiment by ~10 % (measured +9 % mean, +14 % worst up to T = 2.4);
    // the two experiments themselves differ by ~10 % at the same T (gate opening, floor friction).
    CHECK(std::abs(ours - p.Z) / p.Z < 0.20);
    sum += (ours - p.Z) / p.Z;
    ++n;
  }
  REQUIRE(n >= 6);
  std::printf("dam break 2D short: mean front error vs Koshizuka-Oka %+.1f %% over %d points\n", 100 * sum / n, n);
  // The front advances: it never falls back by more than one spacing (l0/a = 0.05), which is what a tip node
  // detaching from the liquid (and so no longer counted as the front) can take away.
  for (std::size_t i = 1; i < T.size(); ++i)
    if (T[i] > 0.5) CHECK(Z[i] >= Z[i - 1] - 0.05);
}
