// Particle-particle contact driver, a template on the contact law (laws.hpp lists them). The driver
// owns the iteration, the geometry stage (sphere_geometry.hpp) the contact, the law the physics.
// Per step:
//   1. prefilter: the overlap test over every pair of the Verlet list, in xsimd batches (for a law
//      that acts before touching, ReachingLaw, within r_i + r_j + its reach: a negative overlap);
//   2. compaction of the touching pairs into a packed contact list, in list order, merged with the
//      packed history of the last evaluation (pairs that separated drop theirs);
//   3. geometry and law over the packed contacts in xsimd batches (a scalar tail), history read and
//      written with vector loads and stores, per-contact force and the torques on both sides;
//   4. the sums into Force and Torque, by fixed slabs of slab_rows(n) owner rows, right after the
//      law has run over the slab's contacts (steps 3 and 4 are one task per slab, so the law's
//      outputs are summed while in cache): a slab's contacts add into its own rows in contact order
//      (owner and partner side), and the partner sides that fall in a later slab are set aside per
//      target slab, then added there, slab by slab (no atomics). Ghost rows (periodic images) are
//      target slabs past the owned ones: their Force and Torque start from zero each evaluation.
// Every step is independent of the thread count, so runs are bit-for-bit repeatable.
// Lever arms are L = r - delta/2 on each side (centre to contact point).
// compute_pair_forces_scalar is the plain reference the tests and benchmarks compare with.
//
// Reads:  Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable.
// Writes: Force, Torque, PairHistory, PairForces.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/system.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/contact/contact_law.hpp"
#include "systems/contact/contact_table.hpp"
#include "systems/contact/vec3.hpp"
#include "systems/integrate/force_terms.hpp"
#include "systems/stability/stability_report.hpp"

namespace gf {

struct PairForces {
  // Packed contacts of the last evaluation, in list order (one slack row past the end).
  // (The list index of each contact is next.pair while the step runs, then the live springs' pair.)
  Column<std::int32_t> ci, cj;     // its rows
  Column<std::int32_t> ctype;      // its type-pair index (NeighborList::type_pair)
  Column<std::int32_t> cslot;      // its spring's entry in the history of the last evaluation, or -1
  // Per contact (one slack row past the end): force on the owner i (N; j gets minus it).
  ColumnD fx, fy, fz;
  // Torques on i and on j (N m) live in a per-task buffer while their slab is summed (they are
  // read once, right away); with record_torques set they are also kept here per contact.
  bool record_torques = false;
  ColumnD tix, tiy, tiz, tjx, tjy, tjz;
  // Per list pair.
  Column<std::uint8_t> touching;       // overlap flag per list pair
  PairHistory next;                    // springs being written, swapped with the live ones
  std::vector<std::uint32_t> block_start;  // contacts before each block of list pairs
  std::vector<double> coeff[kMaxConstants];  // the law's constants per type pair (index q, type pair)
  bool coeff_uniform[kMaxConstants] = {};
  // Partner sides that land past their owner's slab: one list per (owner slab, target slab).
  struct Spill {
    std::uint32_t j;
    double fx, fy, fz, tx, ty, tz;
  };
  std::vector<std::vector<Spill>> spill;
  std::vector<std::uint8_t> block_over;  // per prefilter block: some pair overlaps past the limit
  std::vector<double> reach;  // a law acting before touching: its reach (m) per type pair (NeighborList::type_pair)

  std::size_t contacts() const { return ci.size() - 1; }
  // Force on the owner of list pair k at the last evaluation (zero when apart), given the springs
  // that evaluation left (their slot map names each pair's contact).
  V3<double> force_of(const PairHistory& live, std::size_t k) const {
    const std::int32_t c = live.slot[k];
    if (c < 0) return {0.0, 0.0, 0.0};
    return {fx[static_cast<std::size_t>(c)], fy[static_cast<std::size_t>(c)], fz[static_cast<std::size_t>(c)]};
  }
};

// Owner rows per slab of the force sums, for n owned rows: about n / 16 (work for several threads),
// 256 to 2,048 (a slab's rows and contacts stay in cache), a multiple of 64. A function of n alone,
// not of the thread count, so the order of every addition, and the result, is the same with any
// number of threads.
inline std::size_t slab_rows(std::size_t n) {
  const std::size_t s = (n / 16 + 63) / 64 * 64;
  return s < 256 ? 256 : (s > 2048 ? 2048 : s);
}

// Throws StabilityError naming the deepest pair past `limit` (run.max_overlap), the step and the fix.
[[noreturn]] void report_pair_overlap(const Grains& g, const PairForces& contacts, double limit,
                                      const StepContext& step);

// Evaluates every pair of `list` with law L and sums per row into Force and Torque. Instantiated
// for every law of ContactLaws. Returns whether some pair overlaps by more than overlap_limit of the
// smaller diameter (run.max_overlap, at most 1), found in the same pass (the overlap test of every
// list pair).
template <class L>
bool compute_pair_forces(Grains& g, const NeighborList& list, PairHistory& history, const ContactTable& table,
                         double dt, PairForces& out, double overlap_limit = 1.0);
template <class L>
bool compute_pair_forces_scalar(Grains& g, const NeighborList& list, PairHistory& history, const ContactTable& table,
                                double dt, PairForces& out,
                                double overlap_limit = 1.0);

// The integrator's term this system fills.
inline ForceTerm pair_force_term() { return force_term<Force, Torque>("pair_contact"); }

template <class L>
class PairContact : public SystemBase<PairContact<L>> {
 public:
  using Reads = gf::Reads<Position, Velocity, AngularVelocity, Radius, Species, NeighborList, ContactTable, OverlapLimit>;
  using Writes = gf::Writes<Force, Torque, PairHistory, PairForces>;
  std::string_view name() const override { return "pair_contact"; }
  void run(World& world, const StepContext& step) override {
    const double limit = world.resources.get<OverlapLimit>().ratio;
    PairForces& out = world.resources.get<PairForces>();
    if (compute_pair_forces<L>(world.grains, world.resources.get<NeighborList>(), world.resources.get<PairHistory>(),
                               world.resources.get<ContactTable>(), step.dt, out, limit))
      report_pair_overlap(world.grains, out, limit, step);
  }
};

}  // namespace gf
