// The key table of a [[wall]] (engine/field_table.hpp): the analytic walls' and the mesh walls'
// readers read through it, and the manual's reference is generated from it.
#pragma once

#include "engine/field_table.hpp"

namespace gf {

extern const FieldTable kWallFields;  // [[wall]]

}  // namespace gf
