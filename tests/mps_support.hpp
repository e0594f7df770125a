// Helpers shared by the liquid tests: run a scene file for a while and average an observable.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "systems/mps/liquid_observables.hpp"
#include "systems/mps/liquid_simulation.hpp"

namespace gf::test {

inline std::string liquid_scene(const std::string& name) {
  return std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/liquid/" + name;
}

inline std::size_t column_index(const std::string& name) {
  const auto cols = liquid_series_columns();
  for (std::size_t c = 0; c < cols.size(); ++c)
    if (cols[c] == name) return c;
  throw std::invalid_argument("no liquid series column " + name);
}

struct Samples {
  std::vector<std::vector<double>> rows;  // one per step, liquid_series_columns() order
  double mean(const std::string& col, double t0) const {
    const std::size_t c = column_index(col);
    double s = 0, n = 0;
    for (const auto& r : rows)
      if (r[0] >= t0) {
        s += r[c];
        n += 1;
      }
    return s / n;
  }
  double rms(const std::string& col, double t0) const {
    const double m = mean(col, t0);
    const std::size_t c = column_index(col);
    double s = 0, n = 0;
    for (const auto& r : rows)
      if (r[0] >= t0) {
        s += (r[c] - m) * (r[c] - m);
        n += 1;
      }
    return std::sqrt(s / n);
  }
};

// Runs `steps` steps, sampling every `every` steps (and the initial state).
inline Samples run_and_sample(LiquidSimulation& sim, std::int64_t steps, std::int64_t every = 1) {
  Samples s;
  s.rows.push_back(sample_liquid(sim.world(), sim.scene()));
  for (std::int64_t k = 1; k <= steps; ++k) {
    sim.step_once();
    if (k % every == 0) s.rows.push_back(sample_liquid(sim.world(), sim.scene()));
  }
  return s;
}

}  // namespace gf::test
