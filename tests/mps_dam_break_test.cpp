// Dam break, 2D, Koshizuka-Oka geometry (scenes/liquid/dam_break_2d.toml), short version: the surge front up to
// T = t sqrt(2 g/a) = 2.4 against the experiments. The full run (to the far wall, finer l0) and the 3D version
// are in tests/validation/mps_dam_break_validation_test.cpp.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mps_support.hpp"
#include "mps_support_dam.hpp"

using namespace gf;

TEST_CASE("2D dam break, l0 = a/20: surge front within 20 % of the Koshizuka-Oka experiment up to T = 2.4") {
  const double a = 0.146, g = 9.81;
  auto sim = LiquidSimulation::from_file(test::liquid_scene("dam_break_2d.toml"));
  const double t_end = 2.4 / std::sqrt(2 * g / a);
  const std::int64_t steps = std::llround(t_end / sim.scene().dt);
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, steps);
  const test::LiquidCost cost = test::cost_of(sim, steps, test::seconds_since(t0));
  std::vector<double> T, Z;
  const std::size_t c = test::column_index("surge_front");
  for (const auto& r : s.rows) {
    T.push_back(r[0] * std::sqrt(2 * g / a));
    Z.push_back(r[c] / a);
  }
  // At t = 0 the front is the column's face.
  CHECK(Z.front() == Approx(1.0).epsilon(1e-12));
  double sum = 0, worst = 0;
  int n = 0;
  for (const auto& p : test::front_experiments()) {
    if (p.source != "koshizuka_oka_1996" || p.T > 2.4 || p.T == 0) continue;
    const double ours = test::interpolate(T, Z, p.T);
    CAPTURE(p.T, p.Z, ours);
    // 20 %: at this resolution MPS leads the experiment by ~10 % (measured +9 % mean, +14 % worst up to T = 2.4);
    // the two experiments themselves differ by ~10 % at the same T (gate opening, floor friction).
    CHECK(std::abs(ours - p.Z) / p.Z < 0.20);
    sum += (ours - p.Z) / p.Z;
    worst = std::max(worst, std::abs(ours - p.Z) / p.Z);
    ++n;
  }
  REQUIRE(n >= 6);
  std::printf("dam break 2D short: mean front error vs Koshizuka-Oka %+.1f %% over %d points\n", 100 * sum / n, n);
  // The same comparison against Martin & Moyce's points up to T = 2.4, reported (not checked).
  double mm_sum = 0, mm_worst = 0;
  int mm_n = 0;
  for (const auto& p : test::front_experiments()) {
    if (p.source != "martin_moyce_a2.25in" || p.T > 2.4 || p.T == 0) continue;
    const double e = (test::interpolate(T, Z, p.T) - p.Z) / p.Z;
    mm_sum += e;
    mm_worst = std::max(mm_worst, std::abs(e));
    ++mm_n;
  }
  const std::string name = "dam break 2D, a = 0.146 m, l0 = a/20 (scene default), front Z/a for T <= 2.4";
  const std::string ko = "Koshizuka & Oka 1996 experiment (" + std::to_string(n) + " points)";
  const std::string mm = "Martin & Moyce 1952 experiment (" + std::to_string(mm_n) + " points)";
  test::record_liquid("mps_dam_break_test", name, {"front, mean signed error", "", ko, NAN, NAN, 100 * sum / n, ""},
                      cost);
  test::record_liquid("mps_dam_break_test", name,
                      {"front, worst |error|", "", ko, NAN, NAN, 100 * worst, "every point < 20 %"}, cost);
  if (mm_n > 0) {
    test::record_liquid("mps_dam_break_test", name,
                        {"front, mean signed error", "", mm, NAN, NAN, 100 * mm_sum / mm_n, ""}, cost);
    test::record_liquid("mps_dam_break_test", name, {"front, worst |error|", "", mm, NAN, NAN, 100 * mm_worst, ""},
                        cost);
  }
  // The front advances: it never falls back by more than one spacing (l0/a = 0.05), which is what a tip node
  // detaching from the liquid (and so no longer counted as the front) can take away.
  for (std::size_t i = 1; i < T.size(); ++i)
    if (T[i] > 0.5) CHECK(Z[i] >= Z[i - 1] - 0.05);
}
