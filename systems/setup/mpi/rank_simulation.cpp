#include "systems/setup/mpi/rank_simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>

#include "engine/run_loop.hpp"
#include "systems/broadphase/broadphase.hpp"
#include "systems/contact/laws.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/decomposition/mpi/migration.hpp"
#include "systems/decomposition/mpi/rank_flow.hpp"
#include "systems/decomposition/mpi/rank_list_cover.hpp"
#include "systems/decomposition/row_bytes.hpp"
#include "systems/decomposition/row_cost.hpp"
#include "systems/integrate/integrate.hpp"
#include "systems/periodic/periodic_images.hpp"
#include "systems/walls/contact_systems.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/wall_contact.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

namespace {

std::array<double, 3> position(const Grains& g, std::size_t row) { return {g.pos.x[row], g.pos.y[row], g.pos.z[row]}; }

// The bounding box of the grains and of the feeds' regions (where grains will appear), widened by a
// thousand times its largest side on every side.
DomainBox padded_bounds(const Grains& g, const FlowSpec& flow) {
  std::vector<std::array<double, 3>> points;
  for (std::size_t i = 0; i < g.n_owned; ++i) points.push_back(position(g, i));
  for (const FeedSpec& f : flow.feeds) {
    points.push_back(f.region.bbox_lo());
    points.push_back(f.region.bbox_hi());
  }
  DomainBox b;
  b.lo = {0.0, 0.0, 0.0};
  b.hi = {1.0, 1.0, 1.0};
  if (!points.empty()) b.lo = b.hi = points[0];
  for (const auto& p : points)
    for (std::size_t d = 0; d < 3; ++d) {
      b.lo[d] = std::min(b.lo[d], p[d]);
      b.hi[d] = std::max(b.hi[d], p[d]);
    }
  double side = 0.0;
  for (std::size_t d = 0; d < 3; ++d) side = std::max(side, b.hi[d] - b.lo[d]);
  const double pad = 1000.0 * std::max(side, 1e-3);
  for (std::size_t d = 0; d < 3; ++d) b.lo[d] -= pad, b.hi[d] += pad;
  return b;
}

// A spring in flight between ranks: its pair's ids (the first is the grain whose view the values
// are in) and the law's history values.
struct SpringRecord {
  std::int64_t own = 0, other = 0;
  std::array<double, kMaxHistory> value{};
};

void put(std::vector<std::byte>& out, const void* p, std::size_t n) {
  const auto* b = static_cast<const std::byte*>(p);
  out.insert(out.end(), b, b + n);
}

}  // namespace

RankSimulation::RankSimulation(DemScene scene, const MpiContext& mpi) : mpi_(&mpi) {
  if (scene.bodies)
    throw std::invalid_argument("a scene of composite bodies runs on ranks through run_rank_body_command "
                                "(grainflow_mpi does so), not as a RankSimulation");
  periodic_ = scene.periodic;
  max_grains_ = memory_grain_limit(scene);
  const FlowSpec scene_flow = scene.flow;
  sim_ = std::make_unique<DemSimulation>(std::move(scene));
  World& w = sim_->world();
  Grains& g = w.grains;
  const DemScene& s = sim_->scene();

  // Every rank placed the same grains: the same boxes everywhere, then this rank's rows kept. Along
  // a periodic axis the boxes tile the periodic box, the grains wrapped into it.
  wrap_positions(g, periodic_);
  domain_ = padded_bounds(g, scene_flow);
  for (std::size_t d = 0; d < 3; ++d)
    if (periodic_.on[d]) domain_.lo[d] = periodic_.lo[d], domain_.hi[d] = periodic_.hi[d];
  std::unique_ptr<Rcb> rcb = std::make_unique<Rcb>(domain_, g.pos.x.span().first(g.n_owned), g.pos.y.span().first(g.n_owned),
                                                   g.pos.z.span().first(g.n_owned), std::span<const double>{}, mpi.size());
  rcb_ = std::move(rcb);
  std::vector<std::uint32_t> keep;
  for (std::size_t i = 0; i < g.n_owned; ++i)
    if (rcb_->owner_of(position(g, i)) == mpi.rank()) keep.push_back(static_cast<std::uint32_t>(i));
  keep_and_append(g, keep, {});

  double rmax = 0.0;
  for (const SpeciesSpec& sp : s.species) rmax = std::max(rmax, 0.5 * sp.largest());
  const BroadphaseState& bs = w.resources.get<BroadphaseState>();
  reach_ = 2.0 * rmax + bs.skin + bs.reach;
  set_boxes(std::move(rcb_));

  drift_ = std::make_unique<Schedule>();
  contacts_ = std::make_unique<Schedule>();
  kick_ = std::make_unique<Schedule>();
  drift_->emplace<IntegratePositions>(dem_force_terms(s));
  add_contact_systems(*contacts_, {s.law, !s.walls.empty(), !s.mesh_walls.list.empty()});
  kick_->emplace<IntegrateVelocities>(dem_force_terms(s));
  drift_->build(w);
  contacts_->build(w);
  kick_->build(w);
}

namespace {

// A DEM scene, or a refusal naming what does not run on ranks yet.
DemScene rank_scene(const SceneDoc& doc) {
  if (doc.root().has("liquid"))
    doc.root().fail("liquid", "a liquid scene does not run on several ranks yet",
                    "run it with grainflow on one process (its threads share the node's cores)");
  return load_dem_scene(doc);
}

}  // namespace

RankSimulation RankSimulation::from_text(std::string_view toml, const MpiContext& mpi,
                                         const std::vector<std::string>& overrides) {
  return RankSimulation(rank_scene(SceneDoc::parse(toml, "scene.toml", overrides)), mpi);
}

RankSimulation RankSimulation::from_file(const std::filesystem::path& file, const MpiContext& mpi,
                                         const std::vector<std::string>& overrides) {
  return RankSimulation(rank_scene(SceneDoc::load(file, overrides)), mpi);
}

DemScene RankSimulation::load_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return rank_scene(SceneDoc::load(file, overrides));
}

RankSimulation::RankSimulation(RankSimulation&&) noexcept = default;
RankSimulation::~RankSimulation() = default;

void RankSimulation::pack_spring(std::vector<std::byte>& out, std::int64_t own, std::int64_t other,
                                 const PairHistory& h, std::size_t e) {
  put(out, &own, sizeof own);
  put(out, &other, sizeof other);
  for (std::size_t c = 0; c < h.width; ++c) put(out, &h.value[c][e], sizeof(double));
}

void RankSimulation::rebuild() {
  World& w = sim_->world();
  Grains& g = w.grains;
  const NeighborList& list = w.resources.get<NeighborList>();
  const PairHistory& history = w.resources.get<PairHistory>();
  wrap_positions(g, periodic_);
  for (std::size_t i = 0; i < g.n_owned; ++i)
    if (!rcb_->box(rcb_->owner_of(position(g, i))).contains(position(g, i)))
      throw StabilityError("grain " + std::to_string(g.pid.id[i]) +
                           " left the domain the ranks' boxes tile (the grains' starting bounds widened a "
                           "thousandfold): the run blew up or a grain escaped the walls");
  maybe_rebalance();
  // Each spring to the rank that evaluates its pair after the migration: the higher owner.
  std::vector<std::vector<std::byte>> out(static_cast<std::size_t>(mpi_->size()));
  if (listed_)
    for (std::size_t e = 0; e < history.size(); ++e) {
      const auto k = static_cast<std::size_t>(history.pair[e]);
      const std::uint32_t i = list.i[k], j = list.j[k];
      const int to = std::max(rcb_->owner_of(position(g, i)), rcb_->owner_of(position(g, j)));
      pack_spring(out[static_cast<std::size_t>(to)], g.pid.id[i], g.pid.id[j], history, e);
    }
  relist(out);
}

void RankSimulation::set_boxes(std::unique_ptr<Rcb> rcb) {
  rcb_ = std::move(rcb);
  near_ = box_peers(*rcb_, mpi_->rank(), 2.0 * reach_, &periodic_);
}

void RankSimulation::set_rebalance(double ratio) {
  if (!(ratio == 0.0 || (ratio > 1.0 && std::isfinite(ratio))))
    throw std::invalid_argument("the rebalance ratio must be 0 (never) or above 1");
  rebalance_ = ratio;
}

void RankSimulation::maybe_rebalance() {
  if (rebalance_ <= 0.0) return;
  const Grains& g = sim_->grains();
  // Each owned row weighs its cost (row_cost.hpp), from the list about to be replaced.
  const std::vector<double> cost = row_costs(g, sim_->world().resources.get<NeighborList>());
  double mine = 0.0;
  for (const double c : cost) mine += c;
  const double most = mpi_->max(mine), mean = mpi_->sum(mine) / mpi_->size();
  if (!(most > rebalance_ * mean)) return;
  // Every rank's owned positions and costs to every rank, in rank order: the same points, the same boxes.
  std::vector<std::byte> out;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const std::array<double, 4> p{g.pos.x[i], g.pos.y[i], g.pos.z[i], cost[i]};
    put(out, p.data(), sizeof p);
  }
  const std::vector<std::vector<std::byte>> all =
      mpi_->exchange(std::vector<std::vector<std::byte>>(static_cast<std::size_t>(mpi_->size()), out));
  std::vector<double> x, y, z, w;
  for (const auto& bytes : all)
    for (std::size_t at = 0; at + 4 * sizeof(double) <= bytes.size(); at += 4 * sizeof(double)) {
      double p[4];
      std::memcpy(p, bytes.data() + at, sizeof p);
      x.push_back(p[0]);
      y.push_back(p[1]);
      z.push_back(p[2]);
      w.push_back(p[3]);
    }
  set_boxes(std::make_unique<Rcb>(domain_, x, y, z, w, mpi_->size()));
  ++counters_.rebalances;
}

void RankSimulation::relist(const std::vector<std::vector<std::byte>>& out) {
  World& w = sim_->world();
  Grains& g = w.grains;
  NeighborList& list = w.resources.get<NeighborList>();
  PairHistory& history = w.resources.get<PairHistory>();
  const MpiContext& mpi = *mpi_;
  const std::size_t width = history.width;
  // Grains fed or counted out since the last rebuild join or leave first (their springs, sent by
  // pair key, find no pair and are dropped), then every row goes to its owner.
  if (!g.pending.empty()) {
    g.set_ghosts(0);
    g.apply_pending();
  }
  // The rows' new owners; whether any row or spring must go past the near boxes (then, on every
  // rank alike, this rebuild exchanges among all ranks).
  const std::vector<int> owners = row_owners(g, *rcb_);
  std::vector<char> near(static_cast<std::size_t>(mpi.size()), 0);
  near[static_cast<std::size_t>(mpi.rank())] = 1;
  for (const int r : near_) near[static_cast<std::size_t>(r)] = 1;
  bool far = false;
  for (std::size_t r = 0; r < out.size(); ++r) far = far || (!near[r] && !out[r].empty());
  for (const int r : owners) far = far || !near[static_cast<std::size_t>(r)];
  const bool all = mpi.max(far ? 1.0 : 0.0) > 0.0;
  const std::vector<std::vector<std::byte>> in = all ? mpi.exchange(out) : mpi.exchange(out, near_);
  const std::size_t record = 2 * sizeof(std::int64_t) + width * sizeof(double);
  std::vector<SpringRecord> springs;
  for (const auto& bytes : in) {
    if (bytes.size() % record != 0) throw std::runtime_error("a spring message is not whole springs");
    for (std::size_t at = 0; at < bytes.size(); at += record) {
      SpringRecord r;
      std::memcpy(&r.own, bytes.data() + at, sizeof(std::int64_t));
      std::memcpy(&r.other, bytes.data() + at + sizeof(std::int64_t), sizeof(std::int64_t));
      for (std::size_t c = 0; c < width; ++c)
        std::memcpy(&r.value[c], bytes.data() + at + 2 * sizeof(std::int64_t) + c * sizeof(double), sizeof(double));
      springs.push_back(r);
    }
  }
  // The rows to their owners, then the sorted owned rows, the ghost rows and the list.
  const MigrationCount moved = migrate_rows(g, owners, mpi, all ? nullptr : &near_);
  counters_.wide_rebuilds += all ? 1 : 0;
  counters_.migrated += static_cast<std::int64_t>(moved.sent);
  history.clear();
  PeriodicImages none;
  rebuild_neighbors(g, w.resources.get<BroadphaseState>(), list, history, none, [&](Grains& rows) {
    make_domain_ghosts(rows, *rcb_, reach_, mpi, ghosts_, GhostShell::half, &periodic_);
  });
  counters_.ghosts = static_cast<std::int64_t>(ghosts_.size());
  ++counters_.rebuilds;
  listed_ = true;

  // The springs attached to their pairs in the new list, turned to its owner's view.
  std::unordered_map<std::uint64_t, std::size_t> by_key;
  by_key.reserve(springs.size());
  for (std::size_t f = 0; f < springs.size(); ++f) by_key.emplace(pair_key(springs[f].own, springs[f].other), f);
  const std::size_t np = list.pairs();
  std::vector<std::pair<std::size_t, std::size_t>> found;  // (list pair, spring)
  for (std::size_t k = 0; k < np && !by_key.empty(); ++k) {
    const auto it = by_key.find(list.key[k]);
    if (it != by_key.end()) found.emplace_back(k, it->second);
  }
  history.resize(found.size());
  history.slot.assign(np, -1);
  for (std::size_t e = 0; e < found.size(); ++e) {
    const auto [k, f] = found[e];
    const double sign = g.pid.id[list.i[k]] == springs[f].own ? 1.0 : history.exchange_sign;
    history.pair[e] = static_cast<std::int32_t>(k);
    history.slot[k] = static_cast<std::int32_t>(e);
    for (std::size_t c = 0; c < width; ++c) history.value[c][e] = sign * springs[f].value[c];
  }
}

void RankSimulation::step_once(const StepContext& c) {
  Grains& g = sim_->grains();
  World& w = sim_->world();
  const DemScene& s = sim_->scene();
  FlowState* flow = w.resources.find<FlowState>();
  if (flow && flow_moving(c)) rank_feed_events(g, s.flow, *flow, *rcb_, *mpi_, c.t, max_grains_);
  drift_->run_step(c);
  if (listed_) refresh_domain_ghosts(g, ghosts_, *mpi_);
  BroadphaseState& bs = w.resources.get<BroadphaseState>();
  // 2: rows join or leave here, 1: a row passed half the skin (or no list yet).
  const double mine = !g.pending.empty() ? 2.0 : !listed_ || needs_rebuild(g, bs) ? 1.0 : 0.0;
  const double most = mpi_->max(mine);
  if (most > 0.0) {
    // With periodic faces the list is rebuilt at skin/2, as on one rank (the check's movers are not
    // carried across the faces).
    if (most < 2.0 && listed_ && !periodic_.any() && rank_list_covers(g, bs, w.resources.get<NeighborList>(), *mpi_, near_))
      ++bs.cover.kept;
    else rebuild();
  }
  contacts_->run_step(c);
  fold_domain_ghost_forces(g, ghosts_, *mpi_);
  kick_->run_step(c);
  if (flow && flow_moving(c)) rank_outlet_pass(g, s.flow, *flow, *mpi_, c.t + c.dt);
}

void RankSimulation::prime() {
  World& w = sim_->world();
  StepContext now = next_step(w.clock);
  now.prime = true;
  step_once(now);
  primed_ = true;
  // As DemSimulation::prime: the springs of a new state start from zero.
  w.resources.get<PairHistory>().clear();
  for_each_column(w.grains.extras.get<WallHistory>(), [](auto& col) {
    std::fill(col.begin(), col.end(), typename std::decay_t<decltype(col)>::value_type{});
  });
}

void RankSimulation::advance(std::int64_t n) {
  if (!primed_) prime();
  Clock& clock = sim_->world().clock;
  if (clock.step == 0) clock.t0 = clock.t;
  for (std::int64_t k = 0; k < n; ++k) {
    StepContext c = next_step(clock);
    c.stage = stage_;
    step_once(c);
    counters_.particle_steps += static_cast<double>(sim_->grains().n_owned);
    ++clock.step;
    clock.t = clock.t0 + static_cast<double>(clock.step) * clock.dt;
  }
}

std::int64_t RankSimulation::settle() {
  if (!primed_) prime();
  const std::int64_t n = sim_->scene().settle_steps();
  if (n <= 0) return 0;
  World& w = sim_->world();
  Walls& walls = w.resources.get<Walls>();
  walls.rotation_enabled = false;
  stage_ = "settle";
  advance(n);
  stage_ = "run";
  walls.rotation_enabled = true;
  w.clock.t = 0.0;
  w.clock.step = 0;
  return n;
}

std::int64_t RankSimulation::total_grains() { return mpi_->sum(static_cast<std::int64_t>(grains().n_owned)); }

double RankSimulation::total_kinetic_energy() {
  const Grains& g = grains();
  double e = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double m = g.mass.m[i];
    e += 0.5 * m * (g.vel.x[i] * g.vel.x[i] + g.vel.y[i] * g.vel.y[i] + g.vel.z[i] * g.vel.z[i]);
    if (g.spin && g.mass.inv_inertia[i] > 0.0)
      e += 0.5 / g.mass.inv_inertia[i] *
           (g.omega.x[i] * g.omega.x[i] + g.omega.y[i] * g.omega.y[i] + g.omega.z[i] * g.omega.z[i]);
  }
  return mpi_->sum(e);
}

std::array<double, 3> RankSimulation::total_momentum() {
  const Grains& g = grains();
  std::array<double, 3> p{};
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    p[0] += g.mass.m[i] * g.vel.x[i];
    p[1] += g.mass.m[i] * g.vel.y[i];
    p[2] += g.mass.m[i] * g.vel.z[i];
  }
  return {mpi_->sum(p[0]), mpi_->sum(p[1]), mpi_->sum(p[2])};
}

}  // namespace gf
