// The key tables of the scene sections whose readers read through them (engine/field_table.hpp): the
// reference in the manual is generated from these (tests/scene_fields_test.cpp).
#pragma once

#include <vector>

#include "engine/field_table.hpp"

namespace gf {

extern const FieldTable kRegionFields;  // a fill's, feed's, outlet's or bodies' `region` inline table
extern const FieldTable kDiameterFields;  // a species' `diameter` as a size distribution
extern const FieldTable kFillFields;    // [[fill]]
extern const FieldTable kFeedFields;    // [[feed]]
extern const FieldTable kOutletFields;  // [[outlet]]
extern const FieldTable kSettleFields;  // [settle]
extern const FieldTable kRunFields;     // [run] of a grain scene
extern const FieldTable kSpeciesFields;  // [[species]]
extern const FieldTable kContactFields;  // [contact]'s model; each law's keys: its own table (contact/laws.hpp)
extern const FieldTable kContactPairFields;  // [[contact.pair]]'s species; the law's keys besides
extern const FieldTable kPeriodicFields;  // [periodic]
extern const FieldTable kOutputFields;    // [output] of a grain scene
extern const FieldTable kAnalysisFields;  // [analysis] of a grain scene
extern const FieldTable kLayersFields;  // [analysis.layers]

// Every table with a manual page, in the order the manual gives them.
std::vector<const FieldTable*> scene_field_tables();

}  // namespace gf
