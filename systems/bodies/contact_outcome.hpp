// One member contact's outcome, as body_contact.cpp evaluates it and body_contact_split.cpp carries
// it between processes: the force on the owner (the other body gets minus it), the torques about
// each body's centre of mass, and the law's history after it. Against the walls, a member's
// outcome is the sum over its planes (force, torque_a; delta the largest overlap).
#pragma once

#include <array>

#include <Eigen/Core>

#include "systems/broadphase/neighbor_list.hpp"

namespace gf {

struct ContactOutcome {
  bool touching = false;
  double delta = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque_a = Eigen::Vector3d::Zero(),
                  torque_b = Eigen::Vector3d::Zero();
  std::array<double, kMaxHistory> history{};
};

}  // namespace gf
