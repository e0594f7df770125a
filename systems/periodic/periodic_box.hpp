// A box whose faces along chosen axes are periodic ([periodic] in a scene), and the shifts by whole
// box lengths that carry a copy across them.
#pragma once

#include <array>
#include <vector>

namespace gf {

struct PeriodicBox {
  std::array<bool, 3> on{};         // periodic along x, y, z
  std::array<double, 3> lo{}, hi{};  // m, the box along the periodic axes
  bool any() const { return on[0] || on[1] || on[2]; }
  double length(int d) const { return hi[d] - lo[d]; }
};

// The shifts a copy across the periodic faces may take, in box lengths per axis: every combination
// of -1, 0, +1 over the periodic axes, in a fixed order; with `positive`, only those whose first
// nonzero component is +1 (one of each pair s, -s, and not the zero shift), as images take them.
std::vector<std::array<int, 3>> periodic_shifts(const PeriodicBox& box, bool positive);

// A shift in metres: s[d] box lengths along each axis d (0 along an axis that is not periodic).
std::array<double, 3> shift_metres(const PeriodicBox& box, const std::array<int, 3>& s);

}  // namespace gf
