#include "systems/flow/outlet.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace gf {

std::vector<ExitRecord> outlet_pass(Grains& g, const OutletSpec& spec, OutletState& state, ResidenceLog& log,
                                    double t) {
  if (!(spec.interval > 0.0) || !std::isfinite(spec.interval))
    throw std::invalid_argument("outlet: the interval must be positive and finite");
  if (const std::string p = spec.region.problem(); !p.empty()) throw std::invalid_argument("outlet: region: " + p);
  std::vector<ExitRecord> out;
  if (t < state.next) return out;
  state.next = t + spec.interval;
  std::vector<std::int64_t> queued = g.pending.remove;
  std::sort(queued.begin(), queued.end());
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    if (!spec.region.contains_sphere({g.pos.x[i], g.pos.y[i], g.pos.z[i]}, 0.0)) continue;
    const std::int64_t id = g.pid.id[i];
    if (std::binary_search(queued.begin(), queued.end(), id)) continue;
    g.queue_remove(id);
    ExitRecord r;
    r.id = id;
    r.type = g.species.type[i];
    r.mass = g.mass.m[i];
    if (const auto e = log.entry(id, true)) r.entry = *e;
    r.exit = t;
    state.discharged_mass += r.mass;
    ++state.discharged;
    out.push_back(r);
  }
  return out;
}

}  // namespace gf
