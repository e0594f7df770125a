// RankSimulation::save and restore: one rank's state in its checkpoint part. Everything that the
// next steps read is stored as it is in memory rather than derived again (the ghost rows and their
// owners, the list, the springs, the skin's reference positions), so the row order, the pair order
// and every floating-point sum after a resume are those of the run that was not stopped.
#include <algorithm>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

#include "engine/mpi/rank_failure.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/broadphase/broadphase_checkpoint.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"
#include "systems/setup/mpi/rank_wall_loads.hpp"
#include "systems/decomposition/row_bytes.hpp"
#include "systems/flow/flow_systems.hpp"
#include "systems/broadphase/list_sections.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

namespace {

const char* kSameRun = "resume with the scene (and --set overrides) of the run that wrote the checkpoint, on as many ranks";

std::string column_name(std::size_t k) { return "rank.grains.column." + std::to_string(k); }

// The ghost rows' owners: per rank, the owned rows sent there (flattened with their counts), and
// where the rows received from it lie.
void save_ghosts(CheckpointWriter& out, const DomainGhosts& gh) {
  std::vector<std::uint64_t> sizes;
  std::vector<std::uint32_t> rows;
  for (const auto& s : gh.send) {
    sizes.push_back(s.size());
    rows.insert(rows.end(), s.begin(), s.end());
  }
  out.vector("rank.ghosts.send_sizes", std::move(sizes));
  out.vector("rank.ghosts.send_rows", std::move(rows));
  out.vector("rank.ghosts.first", gh.first);
  out.vector("rank.ghosts.count", gh.count);
  // Across periodic faces: each copy's shift, per rank beside its rows (none without faces).
  std::vector<double> shifts;
  for (const auto& sh : gh.shift)
    for (const auto& v : sh) shifts.insert(shifts.end(), v.begin(), v.end());
  if (!shifts.empty()) out.vector("rank.ghosts.send_shifts", std::move(shifts));
}

template <class T>
bool all_below(const T& v, std::size_t n) {
  return std::all_of(v.begin(), v.end(), [n](auto x) { return x >= 0 && static_cast<std::size_t>(x) < n; });
}

void restore_ghosts(const CheckpointReader& in, DomainGhosts& gh, const Grains& g, std::size_t ranks) {
  std::vector<std::uint64_t> sizes;
  std::vector<std::uint32_t> rows;
  in.vector("rank.ghosts.send_sizes", sizes);
  in.vector("rank.ghosts.send_rows", rows);
  in.vector("rank.ghosts.first", gh.first);
  in.vector("rank.ghosts.count", gh.count);
  in.require(sizes.size() == ranks && gh.first.size() == ranks && gh.count.size() == ranks, "ghost lists", kFixResume);
  in.require(all_below(rows, g.n_owned), "rows sent as ghosts", kFixResume);
  gh.send.assign(ranks, {});
  std::size_t at = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    in.require(sizes[r] <= rows.size() - at, "ghost list sizes", kFixResume);
    gh.send[r].assign(rows.begin() + static_cast<std::ptrdiff_t>(at), rows.begin() + static_cast<std::ptrdiff_t>(at + sizes[r]));
    at += sizes[r];
    in.require(gh.first[r] >= g.n_owned && gh.first[r] <= g.n && gh.count[r] <= g.n - gh.first[r], "ghost rows", kFixResume);
  }
  gh.shift.assign(ranks, {});
  if (!in.has("rank.ghosts.send_shifts")) return;
  std::vector<double> shifts;
  in.vector("rank.ghosts.send_shifts", shifts);
  in.require(shifts.size() == 3 * rows.size(), "ghost shifts", kFixResume);
  at = 0;
  for (std::size_t r = 0; r < ranks; ++r)
    for (std::size_t k = 0; k < sizes[r]; ++k, at += 3) gh.shift[r].push_back({shifts[at], shifts[at + 1], shifts[at + 2]});
}

void check_domain(const CheckpointReader& in, const DomainBox& now_domain);

// The law, dt, the skin, spins and the grains' columns of the part against this run's.
void check_settings(const CheckpointReader& in, const DemScene& s, double skin, Grains& g) {
  std::vector<char> law;
  in.vector("rank.contact.law", law);
  if (std::string(law.begin(), law.end()) != s.law)
    in.fail("it was written with the contact law '" + std::string(law.begin(), law.end()) + "', the scene now uses '" +
                s.law + "'",
            kSameRun);
  if (in.value<double>("rank.clock.dt") != s.dt) in.fail("it was written with another run.dt", kSameRun);
  if (in.value<double>("rank.broadphase.skin") != skin) in.fail("it was written with another run.skin", kSameRun);
  if (in.value<bool>("rank.grains.spin") != g.spin) in.fail("it was written for grains that rotate otherwise", kSameRun);
  if (in.value<std::uint64_t>("rank.grains.columns") != raw_row_columns(g).size())
    in.fail("its grains have other columns than this scene's", kSameRun);
}

// The rank, the rank count and the domain of the part against this run's.
void check_run(const CheckpointReader& in, const MpiContext& mpi, const DomainBox& now_domain) {
  const auto ranks = in.value<std::int32_t>("rank.ranks");
  if (ranks != mpi.size())
    in.fail("it is a part of a checkpoint of " + std::to_string(ranks) + " ranks, this run has " +
                std::to_string(mpi.size()),
            "resume on " + std::to_string(ranks) + " ranks (mpiexec -n " + std::to_string(ranks) + ")");
  if (in.value<std::int32_t>("rank.rank") != mpi.rank())
    in.fail("it is rank " + std::to_string(in.value<std::int32_t>("rank.rank")) + "'s part, read by rank " +
                std::to_string(mpi.rank()),
            "resume from the checkpoint's index file, which names each rank's part");
  check_domain(in, now_domain);
}

// The domain the part's boxes tile against this run's: the scene's starting grains give it.
void check_domain(const CheckpointReader& in, const DomainBox& now_domain) {
  const auto domain = in.value<DomainBox>("rank.domain");
  if (std::memcmp(&domain, &now_domain, sizeof domain) != 0)
    in.fail("the domain its ranks' boxes tile is not the one this scene's grains give (another fill, seed or grain "
            "count)",
            kSameRun);
}

// The ranks' boxes and their cut tree as the part holds them (cut again when the run rebalanced).
std::unique_ptr<Rcb> restore_rcb(const CheckpointReader& in, int ranks) {
  std::vector<DomainBox> boxes;
  std::vector<RcbNode> nodes;
  in.vector("rank.boxes", boxes);
  in.vector("rank.rcb.nodes", nodes);
  if (boxes.size() != static_cast<std::size_t>(ranks)) in.fail("it holds another number of boxes than ranks", kSameRun);
  try {
    return std::make_unique<Rcb>(std::move(nodes), std::move(boxes));
  } catch (const std::invalid_argument& e) {
    in.fail(std::string("its boxes are inconsistent: ") + e.what(), "resume from an earlier checkpoint");
  }
}

// The clock and the walls' state (the same in every part of one checkpoint).
void restore_clock(const CheckpointReader& in, World& w) {
  w.clock.t = in.value<double>("rank.clock.t");
  w.clock.dt = in.value<double>("rank.clock.dt");
  w.clock.step = in.value<std::int64_t>("rank.clock.step");
  w.clock.t0 = in.value<double>("rank.clock.t0");
  Walls& walls = w.resources.get<Walls>();
  walls.rotation_enabled = in.value<bool>("rank.walls.rotation_enabled");
  walls.place(w.clock.t);
}

}  // namespace

void RankSimulation::save(CheckpointWriter& out) {
  World& w = sim_->world();
  Grains& g = w.grains;
  const DemScene& s = sim_->scene();
  out.value("rank.ranks", static_cast<std::int32_t>(mpi_->size()));
  out.value("rank.rank", static_cast<std::int32_t>(mpi_->rank()));
  out.value("rank.domain", domain_);
  out.vector("rank.boxes", rcb_->boxes());
  out.vector("rank.rcb.nodes", rcb_->nodes());
  out.vector("rank.contact.law", std::vector<char>(s.law.begin(), s.law.end()));
  out.value("rank.clock.t", w.clock.t);
  out.value("rank.clock.dt", w.clock.dt);
  out.value("rank.clock.step", w.clock.step);
  out.value("rank.clock.t0", w.clock.t0);
  out.value("rank.grains.n_owned", static_cast<std::uint64_t>(g.n_owned));
  out.value("rank.grains.n", static_cast<std::uint64_t>(g.n));
  out.value("rank.grains.spin", g.spin);
  const std::vector<RawColumn> cols = raw_row_columns(g);
  out.value("rank.grains.columns", static_cast<std::uint64_t>(cols.size()));
  for (std::size_t k = 0; k < cols.size(); ++k) out.raw(column_name(k), cols[k].data, cols[k].elem_size, cols[k].size);
  BroadphaseState& bp = w.resources.get<BroadphaseState>();
  save_broadphase(out, bp, "rank.");
  out.value("rank.walls.rotation_enabled", w.resources.get<Walls>().rotation_enabled);
  save_rank_wall_loads(out, w, *mpi_);
  list_sections(out, w.resources.get<NeighborList>(), w.resources.get<PairHistory>(), bp, "rank.");
  save_ghosts(out, ghosts_);
  out.value("rank.listed", listed_);
  out.value("rank.primed", primed_);
  out.value("rank.counters", counters_);
  save_flow(out);
}

void RankSimulation::restore(const CheckpointReader& in) {
  World& w = sim_->world();
  Grains& g = w.grains;
  BroadphaseState& bp = w.resources.get<BroadphaseState>();
  check_run(in, *mpi_, domain_);
  check_settings(in, sim_->scene(), bp.skin, g);
  std::unique_ptr<Rcb> rcb = restore_rcb(in, mpi_->size());
  const auto n_owned = in.value<std::uint64_t>("rank.grains.n_owned");
  const auto n = in.value<std::uint64_t>("rank.grains.n");
  // Every row takes at least 8 bytes per column: a larger count is corrupt, not a reason to allocate.
  in.require(n_owned <= n && n <= in.bytes() / 8, "grain counts", kFixResume);
  g.resize(n);
  g.n_owned = n_owned;
  const std::vector<RawColumn> cols = raw_row_columns(g);
  for (std::size_t k = 0; k < cols.size(); ++k) in.copy_raw(column_name(k), cols[k].data, cols[k].elem_size, n);
  restore_clock(in, w);
  restore_rank_wall_loads(in, w);
  restore_broadphase(in, bp, "rank.");
  NeighborList& list = w.resources.get<NeighborList>();
  PairHistory& history = w.resources.get<PairHistory>();
  list_sections(in, list, history, bp, "rank.");
  check_list_sections(in, list, history, bp, g);
  restore_ghosts(in, ghosts_, g, static_cast<std::size_t>(mpi_->size()));
  set_boxes(std::move(rcb));
  ghosts_.peers = box_peers(*rcb_, mpi_->rank(), reach_, &periodic_);  // as make_domain_ghosts found them
  listed_ = in.value<bool>("rank.listed");
  primed_ = in.value<bool>("rank.primed");
  counters_ = in.value<RankCounters>("rank.counters");
  restore_flow(in, true);
}

void RankSimulation::save_flow(CheckpointWriter& out) {
  World& w = sim_->world();
  const Grains& g = w.grains;
  out.value("rank.grains.next_id", g.next_id);
  out.vector("rank.grains.pending.insert", g.pending.insert);
  out.vector("rank.grains.pending.remove", g.pending.remove);
  if (const FlowState* f = w.resources.find<FlowState>()) save_flow_state(out, *f);
}

void RankSimulation::restore_flow(const CheckpointReader& in, bool own_part) {
  World& w = sim_->world();
  Grains& g = w.grains;
  const DemScene& s = sim_->scene();
  // Parts written before grains could be fed on ranks keep the ids the scene's fill gave.
  if (in.has("rank.grains.next_id")) g.next_id = in.value<std::int64_t>("rank.grains.next_id");
  g.pending = {};
  if (own_part && in.has("rank.grains.pending.insert")) {
    in.vector("rank.grains.pending.insert", g.pending.insert);
    in.vector("rank.grains.pending.remove", g.pending.remove);
  }
  if (s.flow.any()) restore_flow_state(in, w.resources.get<FlowState>(), s.flow);
  else if (in.has("flow.feeds"))
    in.fail("it was written by a run with [[feed]] or [[outlet]] tables, the scene now has none", kSameRun);
}

void RankSimulation::take_part(const CheckpointReader& in, std::int64_t step, PortableParts& parts) {
  Grains& g = sim_->grains();
  check_settings(in, sim_->scene(), parts.broadphase.skin, g);
  if (in.value<std::int64_t>("rank.clock.step") != step)
    in.fail("it holds another step than part 0 of its checkpoint", "resume from an index and parts of one checkpoint");
  const auto n_owned = in.value<std::uint64_t>("rank.grains.n_owned");
  const auto n = in.value<std::uint64_t>("rank.grains.n");
  in.require(n_owned <= n && n <= in.bytes() / 8, "grain counts", kFixResume);
  const std::size_t base = g.n;
  g.resize(base + n);
  const std::vector<RawColumn> cols = raw_row_columns(g);
  for (std::size_t k = 0; k < cols.size(); ++k)
    in.copy_raw(column_name(k), static_cast<std::byte*>(cols[k].data) + base * cols[k].elem_size, cols[k].elem_size, n);
  // The part's springs, by its rows' ids, each to the rank that evaluates its pair under this run's boxes.
  list_sections(in, parts.list, parts.history, parts.broadphase, "rank.");
  const NeighborList& list = parts.list;
  in.require(list.i.size() == list.j.size() && all_below(list.i, n_owned) && all_below(list.j, n) &&
                 all_below(parts.history.pair, list.i.size()),
             "neighbour list rows", kFixResume);
  for (std::size_t e = 0; e < parts.history.size(); ++e) {
    const auto k = static_cast<std::size_t>(parts.history.pair[e]);
    const std::size_t i = base + list.i[k], j = base + list.j[k];
    const int to = std::max(rcb_->owner_of({g.pos.x[i], g.pos.y[i], g.pos.z[i]}),
                            rcb_->owner_of({g.pos.x[j], g.pos.y[j], g.pos.z[j]}));
    pack_spring(parts.springs[static_cast<std::size_t>(to)], g.pid.id[i], g.pid.id[j], parts.history, e);
  }
  for (std::size_t i = 0; i < n_owned; ++i) parts.keep.push_back(static_cast<std::uint32_t>(base + i));
  if (in.has("rank.grains.pending.remove")) {  // grains counted out by an outlet, leaving at the next rebuild
    std::vector<std::int64_t> gone;
    in.vector("rank.grains.pending.remove", gone);
    parts.remove.insert(parts.remove.end(), gone.begin(), gone.end());
  }
  const auto c = in.value<RankCounters>("rank.counters");
  parts.counters.migrated += c.migrated;
  parts.counters.particle_steps += c.particle_steps;
}

void RankSimulation::restore_portable(const CheckpointReader& first, std::span<const std::filesystem::path> mine) {
  World& w = sim_->world();
  Grains& g = w.grains;
  BroadphaseState& bp = w.resources.get<BroadphaseState>();
  const std::int64_t grains = total_grains();  // the scene's, placed by the constructor
  on_every_rank(*mpi_, [&] { check_domain(first, domain_); });
  const auto step = first.value<std::int64_t>("rank.clock.step");
  PortableParts parts{std::vector<std::vector<std::byte>>(static_cast<std::size_t>(mpi_->size())), {}, {},
                      w.resources.get<PairHistory>(), bp, {}, {}};
  g.resize(0);
  // Local reading first, its failure shared (no rank may be left waiting in the collectives after).
  on_every_rank(*mpi_, [&] {
    for (const std::filesystem::path& file : mine) take_part(CheckpointReader(file), step, parts);
  });
  keep_and_append(g, parts.keep, {});  // the parts' ghost rows dropped
  const std::int64_t held = mpi_->sum(static_cast<std::int64_t>(g.n_owned));
  // With feeds and outlets the count is the run's, not the scene's.
  on_every_rank(*mpi_, [&] {
    if (held != grains && !sim_->scene().flow.any())
      first.fail("its parts hold " + std::to_string(held) + " grains, this scene places " + std::to_string(grains),
                 kSameRun);
  });
  restore_clock(first, w);
  restore_rank_wall_loads_portable(first, w, *mpi_);
  bp.rebuilds = first.value<std::int64_t>("rank.broadphase.rebuilds");
  bp.checks = first.value<std::int64_t>("rank.broadphase.checks");
  bp.cover.kept = first.value<std::int64_t>("rank.broadphase.kept");
  counters_ = parts.counters;
  counters_.rebuilds = first.value<RankCounters>("rank.counters").rebuilds;
  // The flow's state is the same in every part.
  on_every_rank(*mpi_, [&] { restore_flow(first, false); });
  g.pending.remove = std::move(parts.remove);
  relist(parts.springs);  // rows to their owners, ghosts, the list, the springs attached
  primed_ = true;
}

}  // namespace gf
