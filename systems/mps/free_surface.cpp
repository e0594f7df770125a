#include "systems/mps/free_surface.hpp"

namespace gf {

std::size_t detect_free_surface(FluidNodes& f, const LiquidParams& lp, std::span<const double> eps) {
  const double limit = lp.beta * lp.k.n0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const bool s = lp.free_surface && f.kind[i] != kDummy && f.n[i] < (eps.empty() ? limit : limit * eps[i]);
    f.surface[i] = s;
    count += s;
  }
  return count;
}

}  // namespace gf
