#include "systems/mps/liquid_fields.hpp"

namespace gf {

std::vector<const FieldTable*> liquid_field_tables() { return {}; }

}  // namespace gf
