// [[feed]] and [[outlet]] tables of a DEM scene (continuous operation, systems/flow/):
//
//   [[feed]]
//   mass_rate = 0.05                        # kg/s, every species together
//   fractions = { sand = 0.7, salt = 0.3 }  # by mass, summing to 1
//   region = { shape = "box", lo = [...], hi = [...] }   # as a [[fill]]'s region
//   velocity = [0, 0, 0]                    # m/s of a new grain (default 0)
//   start = 0.0  stop = 5.0                 # s (defaults: from 0, no end)
//   interval = 0.01                         # s between feed events (default 0.01, at least run.dt)
//   seed = 11                               # default: run.seed + 1000 + the feed's index
//
//   [[outlet]]
//   region = { shape = "box", lo = [...], hi = [...] }   # grains whose centre is inside leave
//   interval = 0.01                         # s between checks (default 0.01, at least run.dt)
#pragma once

#include "systems/flow/flow_systems.hpp"
#include "systems/setup/dem_scene.hpp"

namespace gf {

// Reads the scene's feeds and outlets into s.flow (SceneError naming file, line, key and fix).
void read_flow(DemScene& s, const SceneNode& root);

// The most grains the feeds can insert over the scene's main stage (each event's debt paid in the
// species' grains): an upper bound for the memory check.
std::size_t max_fed_grains(const DemScene& s);

}  // namespace gf
