#include "systems/setup/body_fields.hpp"

namespace gf {

std::vector<const FieldTable*> body_field_tables() { return {}; }

}  // namespace gf
