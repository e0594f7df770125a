// Dam break against the experiments (studies/seed003/results/dam_break_experiments.csv), full runs: 2D at l0 = a/40 until
// the front meets the far wall, and a coarse 3D version (l0 = a/10). Reports the front error per source.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <map>

#include "../mps_support.hpp"
#include "../mps_support_dam.hpp"

using namespace gf;

namespace {

// Mean and worst relative front error per experimental source over the points with Z/a < 3.9; the number of
// points per source goes to `points` when given.
std::map<std::string, std::pair<double, double>> front_errors(const test::Samples& s, const char* label,
                                                              std::map<std::string, int>* points = nullptr) {
  const double a = 0.146, g = 9.81;
  std::vector<double> T, Z;
  const std::size_t c = test::column_index("surge_front");
  for (const auto& r : s.rows) {
    T.push_back(r[0] * std::sqrt(2 * g / a));
    Z.push_back(r[c] / a);
  }
  std::map<std::string, std::pair<double, double>> out;
  std::map<std::string, int> n;
  for (const auto& p : test::front_experiments()) {
    if (p.Z >= 3.9 || p.T == 0 || p.T > T.back()) continue;
    const double e = (test::interpolate(T, Z, p.T) - p.Z) / p.Z;
    auto& [mean, worst] = out[p.source];
    mean += e;
    worst = std::max(worst, std::abs(e));
    ++n[p.source];
  }
  for (auto& [src, v] : out) {
    v.first /= n[src];
    std::printf("%s: front vs %s: mean %+.1f %%, worst %.1f %% (%d points)\n", label, src.c_str(), 100 * v.first,
                100 * v.second, n[src]);
  }
  if (points != nullptr) *points = n;
  return out;
}

// Records the mean and worst front error per source, with the bounds the test checks them against ("" where it
// does not check that figure).
void record_fronts(const std::string& case_name, const std::map<std::string, std::pair<double, double>>& e,
                   const std::map<std::string, int>& n, const test::LiquidCost& cost, const std::string& ko_mean_bound,
                   const std::string& ko_worst_bound, const std::string& mm_mean_bound) {
  const std::map<std::string, std::string> names = {{"koshizuka_oka_1996", "Koshizuka & Oka 1996 experiment"},
                                                    {"martin_moyce_a2.25in", "Martin & Moyce 1952 experiment"}};
  for (const auto& [src, v] : e) {
    const bool ko = src == "koshizuka_oka_1996";
    const std::string ref = names.at(src) + " (" + std::to_string(n.at(src)) + " points)";
    test::record_liquid("mps_dam_break_validation_test", case_name,
                        {"front, mean signed error", "", ref, NAN, NAN, 100 * v.first,
                         ko ? ko_mean_bound : mm_mean_bound},
                        cost);
    test::record_liquid("mps_dam_break_validation_test", case_name,
                        {"front, worst |error|", "", ref, NAN, NAN, 100 * v.second, ko ? ko_worst_bound : ""}, cost);
  }
}

}  // namespace

TEST_CASE("2D dam break, l0 = a/40: surge front against Koshizuka-Oka and Martin-Moyce") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("dam_break_2d.toml"),
                                         {"liquid.l0=0.00365", "run.dt=2.5e-4", "run.duration=0.3"});
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, 1200, 4);
  const test::LiquidCost cost = test::cost_of(sim, 1200, test::seconds_since(t0));
  std::map<std::string, int> n;
  const auto e = front_errors(s, "dam break 2D l0=a/40", &n);
  record_fronts("dam break 2D, l0 = a/40, dt = 2.5e-4 s, front Z/a up to 0.3 s (Z/a < 3.9)", e, n, cost,
                "|mean| < 15 %", "< 25 %", "|mean| < 20 %");
  // The simulated front leads: no gate-opening delay and no floor roughness in the model, and the two
  // experiments differ from each other by ~10 % at the same T. Measured: +10 % mean, 19 % worst against
  // Koshizuka & Oka, +14 % mean against Martin & Moyce. Bounds: 15 % / 25 % / 20 %; a wrong pressure or gravity
  // scale moves the front by far more.
  CHECK(std::abs(e.at("koshizuka_oka_1996").first) < 0.15);
  CHECK(e.at("koshizuka_oka_1996").second < 0.25);
  CHECK(std::abs(e.at("martin_moyce_a2.25in").first) < 0.20);
}

TEST_CASE("3D dam break, l0 = a/10: surge front against Koshizuka-Oka") {
  auto sim = LiquidSimulation::from_file(test::liquid_scene("dam_break_3d.toml"), {"run.duration=0.3"});
  const auto t0 = std::chrono::steady_clock::now();
  const test::Samples s = test::run_and_sample(sim, 300, 2);
  const test::LiquidCost cost = test::cost_of(sim, 300, test::seconds_since(t0));
  std::map<std::string, int> n;
  const auto e = front_errors(s, "dam break 3D l0=a/10", &n);
  record_fronts("dam break 3D, l0 = a/10 (scene default, tank 0.146 m deep), front Z/a up to 0.3 s (Z/a < 3.9)", e, n,
                cost, "|mean| < 20 %", "< 25 %", "");
  // Coarse: 10 nodes across the column; measured +7 % mean, 18 % worst. Bounds 20 % on the mean, 25 % worst.
  CHECK(std::abs(e.at("koshizuka_oka_1996").first) < 0.20);
  CHECK(e.at("koshizuka_oka_1996").second < 0.25);
}
