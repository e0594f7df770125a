// The world: tables of entities plus resources.
#pragma once

#include <cstdint>

#include "engine/grains.hpp"
#include "engine/resources.hpp"
#include "engine/step_context.hpp"
#include "engine/tables.hpp"

namespace gf {

// Simulated time, kept by the stepping loop (run_loop.hpp) and checkpointed; systems are told the
// step they serve through a StepContext. `step` counts completed steps of the current stage.
struct Clock {
  double t = 0.0;   // s
  double dt = 0.0;  // s
  std::int64_t step = 0;
  double t0 = 0.0;  // s, time at step 0 of the stage: t = t0 + step dt, however the stage is split
};

// The context of the next step from a clock (observers, which run between steps, are given the
// time reached: the same values).
inline StepContext next_step(const Clock& c) { return {c.t, c.dt, c.step, 0, 1, false}; }

// One step on: t = t0 + step dt, so that a stage run in pieces (resumed from a checkpoint, or
// advanced in several calls) sees bit-for-bit the same times as one run.
inline void advance_clock(Clock& c) {
  ++c.step;
  c.t = c.t0 + static_cast<double>(c.step) * c.dt;
}

// Systems receive the world explicitly; there are no globals. The grains table is reached directly
// (every DEM system reads it); other tables through `tables`.
struct World {
  World() : grains(tables.add<Grains>()) {}
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  Tables tables;
  Grains& grains;
  Resources resources;
  Clock clock;
};

}  // namespace gf
