// When a periodic output (series rows, frames, pictures, checkpoints) is due: the sampling times lie
// on the grid k * interval, even when the interval is not a multiple of dt, and a time is reached
// up to the clock's round-off (t = t0 + step dt).
#pragma once

namespace gf {

// Due at t >= next, up to round-off of the clock.
inline bool sample_due(double t, double next, double dt) { return t >= next - 1e-6 * dt; }

// The first grid time past t (next is the grid time that was due).
inline double next_sample(double t, double next, double interval, double dt) {
  while (sample_due(t, next, dt)) next += interval;
  return next;
}

}  // namespace gf
