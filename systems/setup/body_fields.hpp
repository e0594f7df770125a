// The key tables of a composite-grain scene's own sections (engine/field_table.hpp): the body scene's
// reader reads through them, and the manual's reference is generated from them
// (tests/scene_fields_test.cpp).
#pragma once

#include <vector>

#include "engine/field_table.hpp"

namespace gf {

// Every composite-grain table with a manual page, in the order the manual gives them.
std::vector<const FieldTable*> body_field_tables();

}  // namespace gf
