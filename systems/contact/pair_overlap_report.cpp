// The message of a pair overlap past run.max_overlap (pair_contact.hpp): the deepest pair, by id.
// Its own unit, so that the kernels' units (pair_contact.cpp) compile to the code they had.
#include <algorithm>
#include <cmath>

#include "engine/run_loop.hpp"
#include "engine/scene.hpp"
#include "systems/stability/stability_report.hpp"
#include "systems/contact/pair_contact.hpp"

namespace gf {

void report_pair_overlap(const Grains& g, const PairForces& c, double limit, const StepContext& step) {
  double worst = -1.0;
  std::size_t at = 0, past = 0;
  for (std::size_t k = 0; k < c.contacts(); ++k) {
    const auto i = static_cast<std::size_t>(c.ci[k]), j = static_cast<std::size_t>(c.cj[k]);
    const double dx = g.pos.x[j] - g.pos.x[i], dy = g.pos.y[j] - g.pos.y[i], dz = g.pos.z[j] - g.pos.z[i];
    const double delta = g.radius.r[i] + g.radius.r[j] - std::sqrt(dx * dx + dy * dy + dz * dz);
    const double ratio = delta / (2.0 * std::min(g.radius.r[i], g.radius.r[j]));
    past += ratio > limit;
    if (ratio > worst) worst = ratio, at = k;
  }
  const auto i = static_cast<std::size_t>(c.ci[at]), j = static_cast<std::size_t>(c.cj[at]);
  throw StabilityError(grain_words(g, i) + " and " + grain_words(g, j) + " overlap by " + short_number(worst) +
                       " of the smaller diameter " + step_words(step) + ", past run.max_overlap = " +
                       short_number(limit) + " (" + std::to_string(past) + " contacts past it). " + overlap_fix(step) +
                       ", or raise run.max_overlap if such overlaps are intended");
}

}  // namespace gf
