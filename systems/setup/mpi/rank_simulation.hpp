// A DEM scene stepped on several ranks: each rank holds the grains of its box of a recursive
// coordinate bisection and copies (ghost rows) of its lower-numbered neighbours' grains near it.
//
// Every rank loads the scene and places the same grains; the boxes are cut from those starting
// positions (rcb.hpp, every grain weighing 1), and each rank keeps the
// grains in its box. The domain the boxes tile is the bounding box of the grains and the feeds'
// regions widened by a thousand times its largest side on every side (the same margin on every axis
// keeps the cuts' order); a grain that leaves it stops the run. The boxes are cut again when the
// load drifts out of balance (set_rebalance).
//
// Messages go to the neighbouring boxes only (MpiContext::exchange with peers): the ghost rows to
// the boxes within reach, and at a rebuild the migrating rows and the springs to the boxes within
// two reaches (a row moves less than a skin between rebuilds, a spring's pair spans at most one
// reach); when the boxes were cut again, or a row or spring must go farther, that rebuild's
// rows and springs go through an exchange among all ranks, which every rank agrees on first.
//
// One step, on the thread that made the MpiContext (the oneTBB graphs run inside each phase):
//   1. the opening half-kick and drift of the owned rows (IntegratePositions);
//   2. the ghost rows refreshed from their owners (position, velocity, spin); then, when any rank
//      sees a row past half the skin (or no list yet) and the lists do not cover every touching
//      pair, every rank rebuilds: the rows whose centre
//      left the rank's box migrate to their new owner (migration.hpp), the owned rows are sorted,
//      the ghost rows are made (domain_ghosts.hpp, half shell: rows of lower ranks within the
//      largest diameter + skin + the law's reach of the box) and appended before the neighbour
//      search, which lists them with the owned rows as it lists periodic images;
//   3. pair, plane-wall and mesh-wall contacts (walls act on owned rows only);
//   4. the partner-side pair forces left on the ghost rows folded back to their owners;
//   5. the closing half-kick (IntegrateVelocities).
// A pair across ranks is evaluated once, on the higher rank. Pair springs (PairHistory) are carried
// across rebuilds and migrations by pair key: before migrating, every spring is sent to the rank that
// will evaluate its pair (the higher of its grains' new owners) and attached there to the new list.
//
// When the half-skin screen trips on some rank, the list-cover check made across the ranks
// (rank_list_cover.hpp) may keep every rank's list; otherwise every rank rebuilds. A row then moves
// less than a skin between rebuilds, still within the two reaches the exchanges assume.
// Periodic faces: the boxes tile the periodic box along its periodic axes, the owned rows are wrapped
// into it at each rebuild (before they migrate), and the ghost rows include copies across the faces
// (domain_ghosts.hpp); the list is then rebuilt at skin/2 (no list-cover check), as on one rank.
// Feeds and outlets (rank_flow.hpp): the grains fed and counted out are queued as on one rank, and
// a rebuild applies the queue before the rows migrate; a queue on any rank makes every rank rebuild
// (the list-cover check cannot keep a list that rows join or leave).
// Not supported yet (refused at construction): composite bodies.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "engine/schedule.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/broadphase/neighbor_list.hpp"
#include "systems/decomposition/mpi/domain_ghosts.hpp"
#include "systems/decomposition/rcb.hpp"
#include "systems/setup/dem_simulation.hpp"

namespace gf {

struct RankCounters {
  std::int64_t rebuilds = 0;  // neighbour rebuilds (every rank makes the same number)
  std::int64_t migrated = 0;  // rows this rank sent away over the run
  std::int64_t ghosts = 0;    // ghost rows held now
  std::int64_t rebalances = 0;  // times the boxes were cut again (every rank the same)
  std::int64_t wide_rebuilds = 0;  // rebuilds whose rows and springs went among all ranks (the same)
  double particle_steps = 0;  // owned rows summed over the steps advanced
};

class RankSimulation {
 public:
  // Loads the scene on every rank (all grains placed), cuts the boxes and keeps this rank's grains.
  RankSimulation(DemScene scene, const MpiContext& mpi);
  static RankSimulation from_text(std::string_view toml, const MpiContext& mpi,
                                  const std::vector<std::string>& overrides = {});
  static RankSimulation from_file(const std::filesystem::path& file, const MpiContext& mpi,
                                  const std::vector<std::string>& overrides = {});
  // The scene a rank run steps, or a refusal (SceneError naming the file and key) of what does not
  // run on ranks yet (a liquid). Scenes of composite bodies load; they run through
  // run_rank_body_command (app/mpi/rank_body_app.hpp), not this class.
  static DemScene load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});
  RankSimulation(RankSimulation&&) noexcept;
  ~RankSimulation();

  // Rebalancing: at a neighbour rebuild where the costliest rank's rows cost more than `ratio` times
  // the mean (a row's cost: row_cost.hpp, 1 plus its share of the list's pairs), the boxes are cut
  // again from the grains' present positions weighted by their costs (every rank gathers them all:
  // a few MB at a million grains; a parallel median search would replace it at thousands of ranks),
  // and the rows and springs then move to their new owners with the rebuild's migration. The costs
  // are counts of the state, so a resumed run cuts where the uninterrupted one does.
  // 0 (the default) never rebalances; otherwise ratio > 1.
  void set_rebalance(double ratio);

  // Forces of the initial state (nothing moves); the springs then restart from zero, as in
  // DemSimulation::prime. Collective.
  void prime();
  // Advances n steps; primes first if that has not been done. Collective.
  void advance(std::int64_t n);
  // The scene's settling stage (walls not rotating), then the clock back to 0, as
  // DemSimulation::settle. Returns the steps run. Collective.
  std::int64_t settle();

  // This rank's whole state as a checkpoint part (rank_state.cpp): the clock, the boxes, every row
  // it holds (owned and ghost, every column, wall springs included), the neighbour list with the
  // springs it evaluates, the broadphase's reference positions and counters, the ghost rows'
  // owners and the counters. Local (no collective call).
  void save(CheckpointWriter& out);
  // Replaces this rank's state by a part that `save` wrote on the same rank of a run of the same
  // scene on as many ranks; the steps then continue bit for bit. A part of another rank, rank count,
  // scene or boxes is a CheckpointError naming the file, what differs and the fix. Local.
  void restore(const CheckpointReader& in);
  // Replaces the state by a checkpoint written on another number of ranks (rank_state.cpp): this
  // rank reads the parts `mine` (each part read by one rank), keeps their owned rows and the
  // springs of their lists, and both then go to the ranks that own and evaluate them under this
  // run's boxes, through a neighbour rebuild. The run continues as the stopped one would have to
  // round-off, not bit for bit (the boxes change the order of the force sums). `first` is part 0,
  // whose clock and settings every rank checks; a part of another scene or step is a
  // CheckpointError naming the file and the fix. Collective.
  void restore_portable(const CheckpointReader& first, std::span<const std::filesystem::path> mine);

  // This rank's rows: owned first (grains().n_owned), then the ghost rows.
  Grains& grains() { return sim_->grains(); }
  World& world() { return sim_->world(); }
  DemScene& scene() { return sim_->scene(); }
  // The schedules a step runs (drift, contacts, kick; the exchanges between them are not systems).
  std::vector<Schedule*> schedules() { return {drift_.get(), contacts_.get(), kick_.get()}; }
  const Rcb& rcb() const { return *rcb_; }
  const MpiContext& mpi() const { return *mpi_; }
  const RankCounters& counters() const { return counters_; }

  // Sums over all ranks of the owned rows (collective): grains, kinetic energy (translation and
  // rotation, J) and momentum (kg m/s).
  std::int64_t total_grains();
  double total_kinetic_energy();
  std::array<double, 3> total_momentum();

 private:
  void step_once(const StepContext& c);
  // The domain check, then relist with every spring sent to the rank that evaluates its pair next.
  void rebuild();
  // Sends out[r] (packed springs) to rank r, migrates the rows to their owners, makes the ghost rows
  // and the list, and attaches the springs that arrived to their pairs. Collective.
  void relist(const std::vector<std::vector<std::byte>>& out);
  // What restore_portable gathers from the parts it reads: springs per destination rank, the owned
  // rows to keep, the counters summed, and scratch for the parts' lists.
  struct PortableParts {
    std::vector<std::vector<std::byte>> springs;
    std::vector<std::uint32_t> keep;
    NeighborList list;
    PairHistory history;
    BroadphaseState broadphase;
    RankCounters counters;
    std::vector<std::int64_t> remove;  // grains the parts' outlets counted out, not yet removed
  };
  // The ids handed out, the queued row changes and the feeds' and outlets' state, in a part and back
  // (rank_state.cpp). `own_part`: the part is this rank's own (same rank count), whose queue is this
  // rank's; otherwise the queue comes with the parts' rows (take_part).
  void save_flow(CheckpointWriter& out);
  void restore_flow(const CheckpointReader& in, bool own_part);
  // Appends one part's rows (ghosts included, dropped later) and routes its springs. Local.
  void take_part(const CheckpointReader& in, std::int64_t step, PortableParts& parts);
  // The boxes cut again when the rows' costs are out of balance (set_rebalance). Collective.
  void maybe_rebalance();
  // Takes the ranks' boxes, and with them the ranks near this one.
  void set_boxes(std::unique_ptr<Rcb> rcb);
  // One spring packed for relist: its pair's ids (`own` the grain whose view the values are in) and
  // entry e of h's values.
  static void pack_spring(std::vector<std::byte>& out, std::int64_t own, std::int64_t other, const PairHistory& h,
                          std::size_t e);

  const MpiContext* mpi_;
  std::unique_ptr<DemSimulation> sim_;
  std::unique_ptr<Rcb> rcb_;
  std::unique_ptr<Schedule> drift_, contacts_, kick_;
  DomainGhosts ghosts_;
  DomainBox domain_;    // the box the ranks' boxes tile: the starting grains' and feeds' bounds widened (the periodic box along its axes)
  PeriodicBox periodic_;  // the scene's [periodic] faces
  std::vector<int> near_;  // the ranks whose boxes lie within two reaches of this one (set_boxes)
  std::size_t max_grains_ = 0;  // rows a rank's memory holds, for the feeds' check
  std::string_view stage_ = "run";  // "settle" while settling: no feeding nor counting out
  double rebalance_ = 0.0;
  double reach_ = 0.0;  // m, how far from a box a ghost row may lie
  bool listed_ = false;
  bool primed_ = false;
  RankCounters counters_;
};

}  // namespace gf
