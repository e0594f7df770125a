// The key table of a coupled scene's [coupling] section (engine/field_table.hpp): the coupled scene's
// reader (systems/setup/coupled_scene.cpp) reads through it, and the manual's reference on liquid.md is
// generated from it (tests/scene_fields_test.cpp).
#pragma once

#include "engine/field_table.hpp"

namespace gf {

extern const FieldTable kCouplingFields;  // [coupling]

}  // namespace gf
