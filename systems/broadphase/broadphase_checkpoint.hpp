// The broadphase's state in a checkpoint, saved and restored by the broadphase itself for every model
// that has one (one process and ranks): the skin it was built with, whether the list is valid or a
// rebuild is forced, and its counters. The list and the springs it holds are saved beside it
// (systems/broadphase/list_sections.hpp). Sections are named PREFIX + "broadphase." + field.
#pragma once

#include <string>

#include "engine/checkpoint_file.hpp"
#include "systems/broadphase/broadphase.hpp"

namespace gf {

void save_broadphase(CheckpointWriter& out, const BroadphaseState& bp, const std::string& prefix);
// Restores all but the skin, which the caller checks against the scene's first (a checkpoint of
// another skin is refused by name). A checkpoint written before the list could be kept past skin/2
// has no count of it: none.
void restore_broadphase(const CheckpointReader& in, BroadphaseState& bp, const std::string& prefix);

// After the list, the springs and the grain rows are restored (list_sections.hpp): a checkpoint is
// raw arrays sealed by a checksum, and one corrupted and sealed again must still not index past an
// array, so every index and length the list and the springs hold is checked against the rows.
void check_list_sections(const CheckpointReader& in, const NeighborList& list, const PairHistory& history,
                         const BroadphaseState& bp, const Grains& g);

}  // namespace gf
