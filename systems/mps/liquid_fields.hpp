// The key tables of a liquid scene's sections (engine/field_table.hpp): the liquid's readers read
// through them, and the manual's liquid reference is generated from them (tests/scene_fields_test.cpp).
// [coupling]'s table is the coupling's: systems/coupling/coupling_fields.hpp.
#pragma once

#include <vector>

#include "engine/field_table.hpp"

namespace gf {

extern const FieldTable kLiquidFields;          // [liquid]
extern const FieldTable kLiquidSolverFields;    // [liquid]'s `solver` table
extern const FieldTable kLiquidRunFields;       // a liquid scene's [run]
extern const FieldTable kLiquidGeometryFields;  // [geometry]
extern const FieldTable kFluidBlockFields;      // [[fluid]]
extern const FieldTable kDriveFields;           // [drive]
extern const FieldTable kLiquidOutputFields;    // a liquid scene's [output]

// Every liquid table with a manual page, in the order the manual gives them.
std::vector<const FieldTable*> liquid_field_tables();

}  // namespace gf
