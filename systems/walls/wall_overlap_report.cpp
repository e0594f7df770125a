// The message of a wall overlap past run.max_overlap (wall_contact.hpp): the deepest grain, by id,
// and the wall by name. Its own unit, beside the kernels' (wall_contact.cpp).
#include <cmath>

#include "engine/run_loop.hpp"
#include "engine/scene.hpp"
#include "systems/stability/stability_report.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

void report_wall_overlap(const Grains& g, const Walls& walls, double limit, const StepContext& step) {
  double worst = -1.0;
  std::size_t at = 0, wall = 0, past = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    for (std::size_t w = 0; w < walls.list.size(); ++w) {
      Vec3d n;
      const double ratio =
          (g.radius.r[i] - wall_gap(walls.list[w], {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, n)) / (2.0 * g.radius.r[i]);
      past += ratio > limit;
      if (ratio > worst) worst = ratio, at = i, wall = w;
    }
  const std::string name = walls.list.empty() ? std::string("a wall") : "wall '" + walls.list[wall].name + "'";
  throw StabilityError(grain_words(g, at) + " overlaps " + name + " by " + short_number(worst) + " of its diameter " +
                       step_words(step) +
                       ", past run.max_overlap = " + short_number(limit) + " (" + std::to_string(past) +
                       " wall contacts past it). " + overlap_fix(step) +
                       ", or raise run.max_overlap if such overlaps are intended");
}

}  // namespace gf
