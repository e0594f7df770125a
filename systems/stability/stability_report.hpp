// Stability checks of every step. The kernels find the trouble in the pass that produces it (the
// integrator's passes sum s - s over a sum s of what they write, the contact kernels compare each
// pair's squared distance or each wall gap against the overlap limit), at a few operations per row
// or pair; only when one trips is the state searched again, here, to name the step, the grains and
// what to change.
#pragma once

#include <string_view>

#include "engine/grains.hpp"
#include "engine/step_context.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

struct PairForces;

// run.max_overlap: the largest overlap allowed, as a fraction of the smaller diameter of a pair
// (of the grain's diameter against a wall).
struct OverlapLimit {
  double ratio = 0.1;
};

// Each throws StabilityError naming the step, the grain(s) by id and row, and the fix.
[[noreturn]] void report_nonfinite(const Grains& g, const StepContext& step, std::string_view pass);
[[noreturn]] void report_pair_overlap(const Grains& g, const PairForces& contacts, double limit,
                                      const StepContext& step);
[[noreturn]] void report_wall_overlap(const Grains& g, const Walls& walls, double limit, const StepContext& step);

}  // namespace gf
