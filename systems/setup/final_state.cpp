#include "systems/setup/final_state.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "systems/fill/state_csv.hpp"

namespace gf {

void write_final_state(const std::filesystem::path& file, const Grains& g) {
  std::vector<StateRow> rows(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i)
    rows[i] = {g.pid.id[i], g.species.type[i] + 1, 2.0 * g.radius.r[i],
               {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, 0,
               {g.vel.x[i], g.vel.y[i], g.vel.z[i]},
               g.spin ? std::array<double, 3>{g.omega.x[i], g.omega.y[i], g.omega.z[i]} : std::array<double, 3>{}};
  std::sort(rows.begin(), rows.end(), [](const StateRow& a, const StateRow& b) { return a.id < b.id; });
  write_state_csv(file, rows);
}

}  // namespace gf
