// Broadphase: uniform grid by counting sort, rows re-sorted in cell order at every rebuild
// (ties broken by particle id, so the row order depends on positions only, never on input order;
// cells run fastest along the shortest extent of the grains, so neighbours are close in order),
// Verlet skin, rebuild when some row moved more than half the skin since the last rebuild and the
// list can no longer be shown to hold every touching pair (list_cover.hpp: a missing pair touches,
// a row moved a whole skin, or too many rows moved to check).
// Contact history moves with the pair key through rebuilds and re-sorting.
//
// Reads:  Position, Radius, ParticleId.  Writes: every Grains column (rows are permuted; attached
// components move with them), NeighborList, PairHistory, BroadphaseState.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "engine/grains.hpp"
#include "engine/system.hpp"
#include "systems/broadphase/cell_grid.hpp"
#include "systems/broadphase/list_cover.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/broadphase/pair_search.hpp"
#include "systems/periodic/periodic_images.hpp"

namespace gf {

struct BroadphaseState {
  double skin = 0.0;  // m
  double reach = 0.0;  // m, the contact law's largest reach beyond touching (ContactTable::reach; 0 for most)
  bool valid = false;
  bool force_rebuild = false;
  std::int64_t rebuilds = 0;
  std::int64_t checks = 0;
  CellGrid grid;
  PairSearch search;  // by size class, prepared at each rebuild
  ListCover cover;    // the check that may keep the list when a row moved past skin/2
  ColumnD ref_x, ref_y, ref_z;  // positions at the last rebuild
  std::vector<std::vector<std::uint32_t>> partners;  // search scratch per block of rows, reused
  std::vector<std::int64_t> carried;                 // per new list pair: index of its old spring, or -1
  std::vector<std::uint32_t> new_row;                // per old row: its place after re-sorting
};

// One full rebuild: apply the table's queued row inserts and removals, sort rows, find pairs within
// r_i + r_j + reach + skin (reach: the law's, beyond touching), carry history over (a removed grain's springs are dropped, new grains start
// with none).
void rebuild_neighbors(Grains& g, BroadphaseState& state, NeighborList& list, PairHistory& history);
// The same with periodic boundaries: owned rows wrapped into the box, then their images made
// (periodic_images.hpp) and listed with the owned rows they touch.
void rebuild_neighbors(Grains& g, BroadphaseState& state, NeighborList& list, PairHistory& history,
                       PeriodicImages& images);
// The same with ghost rows made elsewhere (a domain decomposition's copies of other ranks' grains):
// once the owned rows are sorted, `add_ghosts` appends them as ghost rows, and the search lists each
// with the owned rows within reach, as it does periodic images. It is not combined with periodic
// faces, and the history must hold no springs on entry (the caller carries them by pair key).
using GhostRowMaker = std::function<void(Grains&)>;
void rebuild_neighbors(Grains& g, BroadphaseState& state, NeighborList& list, PairHistory& history,
                       PeriodicImages& images, const GhostRowMaker& add_ghosts);
// True when the list must be rebuilt whatever the positions: none built yet, a rebuild forced, or
// rows queued for insertion or removal.
bool list_invalid(const Grains& g, const BroadphaseState& state);
// True when some row moved more than skin/2 since the last rebuild, or list_invalid: the screen. The system then rebuilds unless the list
// still holds every touching pair (list_cover.hpp).
bool needs_rebuild(const Grains& g, const BroadphaseState& state);

class Broadphase : public SystemBase<Broadphase> {
 public:
  using Reads = gf::Reads<>;
  using Writes = gf::Writes<Position, Velocity, AngularVelocity, Force, Torque, WallForce, WallTorque, Radius, Mass,
                            Species, ParticleId, NeighborList, PairHistory, BroadphaseState, PeriodicImages>;
  std::string_view name() const override { return "broadphase"; }
  void run(World& world, const StepContext& step) override;
};

}  // namespace gf
