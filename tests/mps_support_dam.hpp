// Experimental surge-front points of the dam break (studies/seed003/results/dam_break_experiments.csv) for the tests.
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace gf::test {

struct FrontPoint {
  std::string source;
  double T, Z;  // T = t sqrt(2 g / a), Z = front / a
};

inline std::vector<FrontPoint> front_experiments() {
  std::ifstream in(std::string(GRAINFLOW_SOURCE_DIR) + "/studies/seed003/results/dam_break_experiments.csv");
  std::vector<FrontPoint> out;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::istringstream s(line);
    FrontPoint p;
    std::string t, z;
    std::getline(s, p.source, ',');
    std::getline(s, t, ',');
    std::getline(s, z, ',');
    p.T = std::stod(t);
    p.Z = std::stod(z);
    out.push_back(p);
  }
  return out;
}

// Linear interpolation of y(x) in sampled (x, y), x increasing.
inline double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  for (std::size_t i = 1; i < x.size(); ++i)
    if (x[i] >= at) return y[i - 1] + (at - x[i - 1]) / (x[i] - x[i - 1]) * (y[i] - y[i - 1]);
  return y.back();
}

}  // namespace gf::test
