// The key tables of a liquid scene's sections (engine/field_table.hpp): the liquid's readers read
// through them, and the manual's liquid reference is generated from them (tests/scene_fields_test.cpp).
#pragma once

#include <vector>

#include "engine/field_table.hpp"

namespace gf {

// Every liquid table with a manual page, in the order the manual gives them.
std::vector<const FieldTable*> liquid_field_tables();

}  // namespace gf
