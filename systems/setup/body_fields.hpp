// The key tables of a composite-grain scene's own sections (engine/field_table.hpp): the body scene's
// reader reads through them, and the manual's reference is generated from them
// (tests/scene_fields_test.cpp).
#pragma once

#include <vector>

#include "engine/field_table.hpp"

namespace gf {

extern const FieldTable kShapeFields;         // [[shape]]
extern const FieldTable kBodiesFields;        // [[bodies]] (its region: kRegionFields)
extern const FieldTable kBodyOutputFields;    // a body scene's [output]
extern const FieldTable kBodyAnalysisFields;  // a body scene's [analysis]
extern const FieldTable kReposeFields;        // [[analysis.repose]]
extern const FieldTable kReposeRegionFields;  // a heap's `region` inline table (a box)
extern const FieldTable kSinkFields;          // [sink]

// Every composite-grain table with a manual page, in the order the manual gives them.
std::vector<const FieldTable*> body_field_tables();

}  // namespace gf
