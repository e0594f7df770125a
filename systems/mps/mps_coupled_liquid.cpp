#include "systems/mps/mps_coupled_liquid.hpp"

#include <algorithm>
#include <cmath>

namespace gf {

std::vector<double> mixture_volumes(std::span<const double> n, double n0, double node_volume) {
  std::vector<double> out(n.size());
  for (std::size_t i = 0; i < n.size(); ++i) out[i] = node_volume * n0 / (n[i] > 0.0 ? std::max(n[i], 0.5 * n0) : n0);
  return out;
}

MpsCoupledLiquid::MpsCoupledLiquid(World& w)
    : f_(w.tables.get<FluidNodes>()),
      params_(w.resources.get<LiquidParams>()),
      fraction_(w.resources.find<LiquidFraction>()),
      volume_(std::pow(params_.k.l0, 3)),
      mass_(params_.rho * volume_) {}

std::vector<double> MpsCoupledLiquid::carrier_volumes() const {
  return mixture_volumes({f_.n.data(), f_.size()}, params_.k.n0, volume_);
}

}  // namespace gf
