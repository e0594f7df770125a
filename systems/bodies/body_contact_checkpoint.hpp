// The member contacts' state in a checkpoint, saved and restored by the body contacts themselves:
// the skin, the member-pair list with its law constants, the springs of member pairs and member-wall
// contacts, the reference centres and the last evaluation's counts. Sections are "body_contact.*".
#pragma once

#include <cstddef>

#include "engine/checkpoint_file.hpp"
#include "systems/bodies/body_contact.hpp"

namespace gf {

void save_body_contact(CheckpointWriter& out, const BodyContactState& s);
// All but the skin, which the caller checks against the scene's first (a checkpoint of another skin
// is refused by name). The springs' layout must be the scene's law's (set_layout) before the call.
// Every index and length is checked against the `members` rows: a checkpoint corrupted and sealed
// again must still not index past an array.
void restore_body_contact(const CheckpointReader& in, BodyContactState& s, std::size_t members);

}  // namespace gf
