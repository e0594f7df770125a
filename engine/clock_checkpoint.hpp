// The clock in a checkpoint: one set of sections (clock.t, clock.dt, clock.step, clock.t0) however many
// parts of a world (grains, liquid) a checkpoint holds.
#pragma once

#include <cstdint>

#include "engine/checkpoint_file.hpp"
#include "engine/world.hpp"

namespace gf {

inline void save_clock(CheckpointWriter& out, const Clock& c) {
  out.value("clock.t", c.t);
  out.value("clock.dt", c.dt);
  out.value("clock.step", c.step);
  out.value("clock.t0", c.t0);
}

inline void restore_clock(const CheckpointReader& in, Clock& c) {
  c.t = in.value<double>("clock.t");
  c.dt = in.value<double>("clock.dt");
  c.step = in.value<std::int64_t>("clock.step");
  c.t0 = in.value<double>("clock.t0");
}

}  // namespace gf
