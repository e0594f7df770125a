// The wall drivers of the laws that act before touching (laws.hpp, ReachingLaws), in a translation unit
// of their own so that the other laws' kernels compile as they did without them.
#include "systems/walls/wall_contact_kernels.hpp"

namespace gf {

extern const auto kWallDriversReaching = wall_drivers(ReachingLaws{});

}  // namespace gf
