// Stability checks of every step. The kernels find the trouble in the pass that produces it (the
// integrator's passes sum s - s over a sum s of what they write, the contact kernels compare each
// pair's squared distance or each wall gap against the overlap limit), at a few operations per row
// or pair; only when one trips is the state searched again, here, to name the step, the grains and
// what to change.
#pragma once

#include <string>
#include <string_view>

#include "engine/grains.hpp"
#include "engine/step_context.hpp"

namespace gf {

// run.max_overlap: the largest overlap allowed, as a fraction of the smaller diameter of a pair
// (of the grain's diameter against a wall).
struct OverlapLimit {
  double ratio = 0.1;
};

// Throws StabilityError naming the step, the grain by id and row, and the fix. The overlap reports
// live beside the contacts that find them (report_pair_overlap in pair_contact.hpp, report_wall_overlap
// in wall_contact.hpp) and word their messages with the helpers below (and engine's short_number).
[[noreturn]] void report_nonfinite(const Grains& g, const StepContext& step, std::string_view pass);

// "in step N of the STAGE stage (t = ... s to ... s)", or "in the initial state (...)".
std::string step_words(const StepContext& step);
// "grain id I (row R)".
std::string grain_words(const Grains& g, std::size_t row);
// The fix of an overlap past run.max_overlap: a smaller step, or (in the initial state) grains placed apart.
std::string overlap_fix(const StepContext& step);

}  // namespace gf
