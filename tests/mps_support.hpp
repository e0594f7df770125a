// Helpers shared by the liquid tests: run a scene file for a while and average an observable, and record the
// figures the validation tests check in the results file the README's liquid validation table is made from.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "systems/mps/free_surface.hpp"
#include "systems/mps/liquid_observables.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/neighbors.hpp"
#include "systems/mps/number_density.hpp"
#include "test_support.hpp"

namespace gf::test {

// The state the PPE sees, from the nodes as they are: neighbours (into nb), number densities, free surface.
inline void prepare_nodes(LiquidSimulation& sim, NeighborPairs& nb) {
  FluidNodes& f = sim.nodes();
  LiquidParams& lp = sim.params();
  build_neighbors(f, lp.k.re + lp.skin, lp.periodic, nb);
  compute_number_density(f, nb, lp.k.re);
  detect_free_surface(f, lp);
}

// A 2D periodic channel of water (l0 = 5 mm), length x height metres, filled completely: no free surface, the
// pressure system closed. `extra`: more [liquid] keys, one per line.
inline std::string full_channel_2d(double length, double height, const std::string& extra = "") {
  std::string size = std::to_string(length) + ", " + std::to_string(height) + ", 0.0]\n";
  std::string text = "[run]\ndt = 1.0e-3\nduration = 0.01\nvelocity_scale = 0.1\n"
                     "[liquid]\ndim = 2\nl0 = 0.005\ndensity = 1000.0\nviscosity = 1.0e-6\n";
  text += extra;
  text += "[geometry]\ntype = \"channel\"\nlo = [0.0, 0.0, 0.0]\nhi = [" + size;
  text += "[[fluid]]\nlo = [0.0, 0.0, 0.0]\nhi = [" + size;
  return text;
}

inline std::string liquid_scene(const std::string& name) {
  // Appended in place: GCC 12 reads `std::string(literal) + "..." + name` as a copy out of bounds
  // (a -Warray-bounds false positive inside libstdc++) when the standard headers are precompiled.
  std::string path = GRAINFLOW_SOURCE_DIR;
  path += "/scenes/liquid/";
  path += name;
  return path;
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

// Seconds of wall-clock time since `t0` (steady clock).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// What a liquid run cost: steps, fluid nodes and wall plus dummy nodes (at the end of the run), the simulated
// time and the wall time of the stepping. NaN and 0 where there was no run (the operator checks).
struct LiquidCost {
  std::int64_t steps = 0;
  std::size_t fluid_nodes = 0, boundary_nodes = 0;
  double simulated_s = std::numeric_limits<double>::quiet_NaN();
  double wall_s = std::numeric_limits<double>::quiet_NaN();
};

inline LiquidCost cost_of(LiquidSimulation& sim, std::int64_t steps, double wall_s) {
  LiquidCost c;
  c.steps = steps;
  c.fluid_nodes = sim.nodes().count(kFluid);
  c.boundary_nodes = sim.nodes().size() - c.fluid_nodes;
  c.simulated_s = static_cast<double>(steps) * sim.scene().dt;
  c.wall_s = wall_s;
  return c;
}

// One figure a liquid test measures: `measured` in `unit`; `reference` (named `reference_name`, NaN where
// there is none) and the signed relative error `error_pct` in percent (NaN where not applicable); `bound` is
// the test's check on the figure in words ("" where the figure is reported, not checked).
struct LiquidFigure {
  std::string quantity, unit, reference_name;
  double reference = std::numeric_limits<double>::quiet_NaN();
  double measured = std::numeric_limits<double>::quiet_NaN();
  double error_pct = std::numeric_limits<double>::quiet_NaN();
  std::string bound;
};

// Appends `f`, with the cost of its run, to validation.csv when GRAINFLOW_RESULTS names a folder
// (studies/seed003/results/validation.csv, turned into the README's liquid validation table by
// studies/seed003/validation_table.py). `test` names the test program, `case_name` the run.
inline void record_liquid(const std::string& test, const std::string& case_name, const LiquidFigure& f,
                          const LiquidCost& c) {
  record_result("validation.csv",
                "test,case,quantity,unit,reference_name,reference,measured,error_pct,bound,steps,fluid_nodes,"
                "boundary_nodes,simulated_s,wall_s",
                csv_field(test) + "," + csv_field(case_name) + "," + csv_field(f.quantity) + "," + csv_field(f.unit) +
                    "," + csv_field(f.reference_name) + "," + csv_number(f.reference, 10) + "," +
                    csv_number(f.measured, 10) + "," + csv_number(f.error_pct, 4) + "," + csv_field(f.bound) + "," +
                    std::to_string(c.steps) + "," + std::to_string(c.fluid_nodes) + "," +
                    std::to_string(c.boundary_nodes) + "," + csv_number(c.simulated_s, 6) + "," +
                    csv_number(c.wall_s, 4));
}

}  // namespace gf::test
