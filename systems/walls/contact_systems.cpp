#include "systems/walls/contact_systems.hpp"

#include <stdexcept>
#include <string>

#include "engine/schedule.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/wall_contact.hpp"

namespace gf {

void add_contact_systems(Schedule& step, const ContactNeeds& needs) {
  const bool known = with_law(needs.law, [&]<class Law>() {
    step.emplace<PairContact<Law>>();
    if (needs.walls) step.emplace<WallContact<Law>>();
    if (needs.meshes) step.emplace<MeshWallContact<Law>>();
  });
  if (!known) throw std::invalid_argument("no contact law is named '" + std::string(needs.law) + "'");
}

}  // namespace gf
