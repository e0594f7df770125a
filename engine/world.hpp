// The world: tables of entities plus resources. Systems receive it explicitly; there are no globals.
#pragma once

#include <cstdint>

#include "engine/grains.hpp"
#include "engine/resources.hpp"

namespace gf {

// Simulated time. `step` counts completed steps of the current stage.
struct Clock {
  double t = 0.0;   // s
  double dt = 0.0;  // s
  std::int64_t step = 0;
  double t0 = 0.0;  // s, time at step 0 of the stage: t = t0 + step dt, however the stage is split
};

struct World {
  Grains grains;
  Resources resources;
  Clock clock;
};

}  // namespace gf
