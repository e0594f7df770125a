// Particle-particle contact driver for the linear spring-dashpot-slider law. The driver owns the
// iteration; the law (linear_spring_dashpot.hpp) owns the physics.
//   phase 1: per pair of the neighbour list, the law's force and the torques on both sides;
//   phase 2: per row, a fixed-order sum over its own pairs then its incoming pairs (no atomics).
// Lever arms are L = r - delta/2 on each side (centre to contact point).
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable, Clock.
// Writes: Force, Torque, PairHistory.
#pragma once

#include "engine/system.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/contact_params.hpp"

namespace gf {

// Per-pair results of phase 1, kept between the phases (and for analysis).
struct PairForces {
  ColumnD fx, fy, fz;     // on the owner row i, N
  ColumnD tix, tiy, tiz;  // torque on i, N m
  ColumnD tjx, tjy, tjz;  // torque on j, N m
  auto columns() { return std::tie(fx, fy, fz, tix, tiy, tiz, tjx, tjy, tjz); }
};

// Evaluates every pair of `list` (phase 1) and sums per row into Force and Torque (phase 2).
void compute_pair_forces(Grains& g, const NeighborList& list, PairHistory& history, const ContactTable& table,
                         double dt, PairForces& out);

class PairContact : public SystemBase<PairContact> {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable, Clock>;
  using Writes = gf::Writes<Force, Torque, PairHistory, PairForces>;
  std::string_view name() const override { return "pair_contact"; }
  void run(World& world) override;
};

}  // namespace gf
