#include "systems/mps/kernel.hpp"

#include <stdexcept>

namespace gf {

MpsConstants lattice_constants(int dim, double l0, double re) {
  if (dim != 2 && dim != 3) throw std::invalid_argument("lattice_constants: dim must be 2 or 3");
  if (!(l0 > 0) || !(re > 0)) throw std::invalid_argument("lattice_constants: l0 and re must be > 0");
  const int m = static_cast<int>(std::ceil(re / l0)) + 1;
  const int mz = dim == 3 ? m : 0;
  double sw = 0, swr2 = 0;
  for (int i = -m; i <= m; ++i)
    for (int j = -m; j <= m; ++j)
      for (int k = -mz; k <= mz; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double r2 = (double(i) * i + double(j) * j + double(k) * k) * l0 * l0;
        const double w = zhang_weight(std::sqrt(r2), re);
        sw += w;
        swr2 += w * r2;
      }
  MpsConstants c;
  c.dim = dim;
  c.l0 = l0;
  c.re = re;
  c.n0 = sw;
  c.lambda = swr2 / sw;
  return c;
}

}  // namespace gf
