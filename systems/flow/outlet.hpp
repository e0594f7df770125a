// The outlet of a continuous scene: grains whose centres have entered the outlet region are queued
// for removal (they leave the table at the next neighbour-list rebuild, which the queue forces at
// the next step) and each leaves a record: its id, species, mass, entry time (when it was fed; NaN
// for a grain present from the start) and exit time. Checked every `interval` seconds, so a grain
// is counted out within one interval of reaching the region.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "engine/grains.hpp"
#include "systems/fill/region.hpp"
#include "systems/flow/feed.hpp"

namespace gf {

struct OutletSpec {
  Region region;
  double interval = 0.0;  // s between checks (> 0)
};

struct ExitRecord {
  std::int64_t id = 0;
  std::int32_t type = 0;
  double mass = 0.0;                                         // kg
  double entry = std::numeric_limits<double>::quiet_NaN();  // s; NaN: not fed (present from the start)
  double exit = 0.0;                                         // s
};

struct OutletState {
  double next = 0.0;              // s, the next check
  double discharged_mass = 0.0;   // kg
  std::int64_t discharged = 0;    // grains
};

// Checks every owned grain not yet queued for removal (if a check is due at time t): those whose
// centre lies in the region are queued and recorded, in row order. std::invalid_argument for a
// region with a problem or an interval that is not positive and finite.
std::vector<ExitRecord> outlet_pass(Grains& g, const OutletSpec& spec, OutletState& state, ResidenceLog& log, double t);

}  // namespace gf
