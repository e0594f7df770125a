// The pair drivers of the laws that act before touching (laws.hpp, ReachingLaws), in a translation unit
// of their own so that the other laws' kernels compile as they did without them.
#include "systems/contact/pair_contact_kernels.hpp"

namespace gf {

extern const auto kPairDriversReaching = pair_drivers(ReachingLaws{});

}  // namespace gf
