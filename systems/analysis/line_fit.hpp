// A least-squares straight line y = intercept + slope x, from points added one at a time (the free
// surfaces of the pattern classifier and of the angle of repose are fitted this way).
#pragma once

#include <cstddef>
#include <limits>

namespace gf {

class LineFit {
 public:
  void add(double x, double y) {
    n_ += 1.0;
    sx_ += x;
    sy_ += y;
    sxx_ += x * x;
    sxy_ += x * y;
  }
  std::size_t points() const { return static_cast<std::size_t>(n_); }
  // NaN with fewer than two points or all x equal.
  double slope() const {
    const double den = n_ * sxx_ - sx_ * sx_;
    return den > 0.0 ? (n_ * sxy_ - sx_ * sy_) / den : std::numeric_limits<double>::quiet_NaN();
  }
  double intercept() const { return (sy_ - slope() * sx_) / n_; }

 private:
  double n_ = 0, sx_ = 0, sy_ = 0, sxx_ = 0, sxy_ = 0;
};

}  // namespace gf
