// Particle-particle contact driver for the linear spring-dashpot-slider law. The driver owns the
// iteration; the law (linear_spring_dashpot.hpp) owns the physics. Per step:
//   1. prefilter: the overlap test over every pair of the Verlet list, in xsimd batches;
//   2. compaction of the touching pairs into a packed contact list, in list order, merged with the
//      packed springs of the last evaluation (pairs that separated drop theirs);
//   3. the law over the packed contacts in xsimd batches (a scalar tail), springs read and written
//      with vector loads and stores, per-contact force and the torques on both sides;
//   4. per row, a fixed-order sum over its own contacts, then its incoming ones (no atomics).
// Every step is independent of the thread count, so runs are bit-for-bit repeatable.
// Lever arms are L = r - delta/2 on each side (centre to contact point).
// compute_pair_forces_scalar is the plain reference the tests and benchmarks compare with.
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable, Clock.
// Writes: Force, Torque, PairHistory, PairForces.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/system.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/contact_params.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

struct PairForces {
  // Packed contacts of the last evaluation, in list order (one slack row past the end).
  Column<std::int32_t> pair;       // list index of each contact
  Column<std::int32_t> ci, cj;     // its rows
  Column<std::int32_t> ctype;      // its type-pair index (NeighborList::type_pair)
  Column<std::int32_t> cslot;      // its spring's entry in the history of the last evaluation, or -1
  // Per contact, for the owner row i's sum (read in contact order): force on i (N) and torque
  // on i (N m); one slot past the last contact is kept zero, for pairs apart.
  ColumnD fx, fy, fz, tix, tiy, tiz;
  // For the partner rows' sums: one 64-byte record per contact {F (force on i; j gets minus it),
  // torque on j, 2 unused}, stored in partner order (by row j, then list order), so that each
  // row's incoming contacts are one contiguous run: `in_start[r]` .. `in_start[r + 1]`.
  static constexpr std::size_t kRecord = 8;
  enum Field : std::size_t { Fx, Fy, Fz, Tjx, Tjy, Tjz };
  ColumnD partner;
  Column<std::int32_t> cpos;          // per contact, its record's position in partner order
  std::vector<std::uint32_t> in_start;  // size rows + 1
  std::vector<std::uint32_t> block_in;  // incoming contacts per block of rows (scratch)
  // Per list pair.
  std::vector<std::int32_t> rank;        // contacts before this list pair (size pairs + 1)
  std::vector<std::int32_t> contact_of;  // contact index, or contacts() (a zero row) when apart
  Column<std::uint8_t> touching;       // overlap flag per list pair
  PairHistory next;                    // springs being written, swapped with the live ones
  std::vector<std::uint32_t> block_start;
  std::vector<double> coeff[8];  // law constants per type pair: kn kt kr eta_n eta_t eta_r fs fr
  bool coeff_uniform[8] = {};

  std::size_t contacts() const { return pair.size() - 1; }
  // Force on the owner of list pair k at the last evaluation (zero when apart).
  V3<double> force_of(std::size_t k) const {
    const auto c = static_cast<std::size_t>(contact_of[k]);
    return {fx[c], fy[c], fz[c]};
  }
};

// Evaluates every pair of `list` and sums per row into Force and Torque.
void compute_pair_forces(Grains& g, const NeighborList& list, PairHistory& history, const ContactTable& table,
                         double dt, PairForces& out);
void compute_pair_forces_scalar(Grains& g, const NeighborList& list, PairHistory& history, const ContactTable& table,
                                double dt, PairForces& out);

class PairContact : public SystemBase<PairContact> {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable, Clock>;
  using Writes = gf::Writes<Force, Torque, PairHistory, PairForces>;
  std::string_view name() const override { return "pair_contact"; }
  void run(World& world) override;
};

}  // namespace gf
