#include "systems/walls/wall_contact_kernels.hpp"

namespace gf {

// The drivers of the laws that act in contact only; those acting before touching: wall_contact_reaching.cpp.
extern const auto kWallDrivers = wall_drivers(TouchingLaws{});

}  // namespace gf
