#include "systems/contact/pair_contact_kernels.hpp"

namespace gf {

// The drivers of the laws that act in contact only; those acting before touching: pair_contact_reaching.cpp.
extern const auto kPairDrivers = pair_drivers(TouchingLaws{});

}  // namespace gf
