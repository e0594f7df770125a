// The liquid fraction eps at each node, for a locally averaged liquid (seed 003's "model B", Anderson and
// Jackson): where grains take part of the volume the liquid's nodes are to sit at the number density
// n~0 = eps n0 instead of n0, so the liquid makes room for the grains (a tank's level rises by their
// volume; grains settling push liquid up). The PPE's density term then reads (n* - eps n0)/n0 and the
// free-surface test n* < beta eps n0. The coupling writes it at the start of every step from the grains'
// positions (coupling.averaged = true); a liquid without it, or with it empty, has eps = 1 everywhere.
#pragma once

#include <span>
#include <vector>

#include "engine/world.hpp"

namespace gf {

struct LiquidFraction {
  std::vector<double> eps;  // per node row, in (0, 1]
};

// The world's liquid fractions, or an empty span (eps = 1) when it has none.
inline std::span<const double> liquid_fraction_of(World& w) {
  const LiquidFraction* f = w.resources.find<LiquidFraction>();
  return f ? std::span<const double>(f->eps) : std::span<const double>();
}

}  // namespace gf
