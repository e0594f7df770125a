#include "systems/periodic/periodic_box.hpp"

namespace gf {

std::vector<std::array<int, 3>> periodic_shifts(const PeriodicBox& box, bool positive) {
  std::vector<std::array<int, 3>> out;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        const std::array<int, 3> s{a, b, c};
        bool ok = true, first_positive = false, seen = false;
        for (int d = 0; d < 3; ++d) {
          if (s[d] != 0 && !box.on[d]) ok = false;
          if (s[d] != 0 && !seen) first_positive = s[d] > 0, seen = true;
        }
        if (ok && (!positive || (seen && first_positive))) out.push_back(s);
      }
  return out;
}

std::array<double, 3> shift_metres(const PeriodicBox& box, const std::array<int, 3>& s) {
  std::array<double, 3> out{};
  for (std::size_t d = 0; d < 3; ++d)
    if (box.on[d]) out[d] = s[d] * box.length(static_cast<int>(d));
  return out;
}

}  // namespace gf
