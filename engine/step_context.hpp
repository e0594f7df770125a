// What a system is told about the step it serves. Systems read time only from here, never from a
// world clock, so the same system can serve an outer step or one of k sub-steps of it.
#pragma once

#include <cstdint>
#include <string_view>

namespace gf {

struct StepContext {
  double t = 0.0;          // s, time at the start of the step (observers: the time now)
  double dt = 0.0;         // s, the step's length (dt/k in a sub-schedule run k times)
  std::int64_t step = 0;   // index of the outer step (observers: steps completed)
  int substep = 0;         // 0 .. substeps-1 inside a sub-schedule, else 0
  int substeps = 1;
  bool prime = false;      // forces of the current state only: nothing moves and no time passes
  // Whether anything reads the state at the end of this step (an observer sampling, the stage's last
  // step). When false, the closing half-kick may be left to the next step's opening pass
  // (integrate.hpp); the stepping loop sets it, and anything else stepping leaves it true.
  bool observed = true;
  std::string_view stage = "run";  // the stage being run ("settle", "run"), for messages
};

}  // namespace gf
