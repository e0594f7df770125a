#include "systems/decomposition/mpi/domain_ghosts.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "systems/decomposition/row_bytes.hpp"

namespace gf {

namespace {

std::vector<ColumnD*> state_columns(Grains& g) {
  std::vector<ColumnD*> c{&g.pos.x, &g.pos.y, &g.pos.z, &g.vel.x, &g.vel.y, &g.vel.z};
  if (g.spin) c.insert(c.end(), {&g.omega.x, &g.omega.y, &g.omega.z});
  return c;
}

std::vector<ColumnD*> force_columns(Grains& g) {
  std::vector<ColumnD*> c{&g.force.x, &g.force.y, &g.force.z};
  if (g.spin) c.insert(c.end(), {&g.torque.x, &g.torque.y, &g.torque.z});
  return c;
}

// The values of the given columns at rows first + k, row after row, as bytes; with shifts (one per
// row), the first three columns (the position) each plus its row's shift.
template <class Rows>
std::vector<std::byte> gather(const std::vector<ColumnD*>& cols, const Rows& rows,
                              const std::vector<std::array<double, 3>>* shift = nullptr) {
  std::vector<double> v;
  v.reserve(rows.size() * cols.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t c = 0; c < cols.size(); ++c) v.push_back(shift && c < 3 ? (*cols[c])[rows[k]] + (*shift)[k][c] : (*cols[c])[rows[k]]);
  std::vector<std::byte> out(v.size() * sizeof(double));
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
}

// The messages out[r] to the peers, and this rank's own (its periodic images) kept here: what each
// rank sent here, this one included.
std::vector<std::vector<std::byte>> exchange_with_self(std::vector<std::vector<std::byte>> out,
                                                       const std::vector<int>& peers, const MpiContext& mpi) {
  const auto me = static_cast<std::size_t>(mpi.rank());
  std::vector<std::byte> own = std::move(out[me]);
  out[me].clear();
  std::vector<std::vector<std::byte>> in = mpi.exchange(out, peers);
  in[me] = std::move(own);
  return in;
}

// Row k of `bytes` (packed as gather packs) for each row in `rows`; add: summed in, else written.
template <class Rows>
void scatter(const std::vector<ColumnD*>& cols, const Rows& rows, const std::vector<std::byte>& bytes, bool add) {
  if (bytes.size() != rows.size() * cols.size() * sizeof(double))
    throw std::runtime_error("a ghost message does not match the ghost rows it is for");
  std::size_t at = 0;
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (ColumnD* c : cols) {
      double x;
      std::memcpy(&x, bytes.data() + at, sizeof(double));
      at += sizeof(double);
      (*c)[rows[k]] = add ? (*c)[rows[k]] + x : x;
    }
}

// Rows first, first + 1, ..., first + count - 1, indexable as a vector of rows.
struct RowRange {
  std::size_t first, count;
  std::size_t size() const { return count; }
  std::size_t operator[](std::size_t k) const { return first + k; }
};

}  // namespace

std::size_t DomainGhosts::size() const {
  std::size_t n = 0;
  for (std::size_t c : count) n += c;
  return n;
}

void make_domain_ghosts(Grains& g, const Rcb& rcb, double reach, const MpiContext& mpi, DomainGhosts& gh,
                        GhostShell shell, const PeriodicBox* periodic) {
  if (rcb.ranks() != mpi.size()) throw std::invalid_argument("the decomposition has another number of ranks");
  if (periodic && !periodic->any()) periodic = nullptr;
  // A rank's own copies across the faces are made for one shift of each pair (s, -s), so each pair
  // across a face is listed once: a full shell, keeping both sides on one rank, would need both.
  if (periodic && shell == GhostShell::full)
    throw std::invalid_argument("ghost rows across periodic faces are made for the half shell only");
  g.set_ghosts(0);
  const auto ranks = static_cast<std::size_t>(mpi.size());
  const int me = mpi.rank();
  gh.send.assign(ranks, {});
  gh.shift.assign(ranks, {});
  gh.peers = box_peers(rcb, me, reach, periodic);
  std::vector<int> targets = gh.peers;
  if (periodic) targets.insert(std::lower_bound(targets.begin(), targets.end(), me), me);
  // Without faces the only shift is zero, and a rank holds no copies of its own rows.
  const PeriodicBox box = periodic ? *periodic : PeriodicBox{};
  const std::vector<std::array<int, 3>> all = periodic_shifts(box, false), own = periodic_shifts(box, true);
  std::vector<std::vector<std::byte>> out(ranks);
  for (const int r : targets) {
    if (shell == GhostShell::half && r < me) continue;
    const auto ru = static_cast<std::size_t>(r);
    auto& rows = gh.send[ru];
    for (std::size_t i = 0; i < g.n_owned; ++i)
      for (const auto& s : r == me ? own : all) {
        const std::array<double, 3> by = shift_metres(box, s);
        if (rcb.box(r).distance({g.pos.x[i] + by[0], g.pos.y[i] + by[1], g.pos.z[i] + by[2]}) > reach) continue;
        rows.push_back(static_cast<std::uint32_t>(i));
        if (periodic) gh.shift[ru].push_back(by);
      }
    pack_rows(g, rows, out[ru], true);
  }
  const std::vector<std::vector<std::byte>> in = exchange_with_self(std::move(out), gh.peers, mpi);
  gh.first.assign(ranks, 0);
  gh.count.assign(ranks, 0);
  std::size_t ghosts = 0;
  for (std::size_t r = 0; r < ranks; ++r) {
    gh.first[r] = g.n_owned + ghosts;
    gh.count[r] = packed_rows(g, in[r].size(), true);
    ghosts += gh.count[r];
  }
  g.set_ghosts(ghosts);
  for (std::size_t r = 0; r < ranks; ++r) unpack_rows(g, in[r], gh.first[r], true);
  // The copies were packed where their owners stand: across a face they stand a shift away.
  if (periodic) refresh_domain_ghosts(g, gh, mpi);
}

void refresh_domain_ghosts(Grains& g, const DomainGhosts& gh, const MpiContext& mpi) {
  const std::vector<ColumnD*> cols = state_columns(g);
  std::vector<std::vector<std::byte>> out(gh.send.size());
  for (std::size_t r = 0; r < out.size(); ++r)
    out[r] = gather(cols, gh.send[r], r < gh.shift.size() && !gh.shift[r].empty() ? &gh.shift[r] : nullptr);
  const std::vector<std::vector<std::byte>> in = exchange_with_self(std::move(out), gh.peers, mpi);
  for (std::size_t r = 0; r < in.size(); ++r) scatter(cols, RowRange{gh.first[r], gh.count[r]}, in[r], false);
}

void fold_domain_ghost_forces(Grains& g, const DomainGhosts& gh, const MpiContext& mpi) {
  const std::vector<ColumnD*> cols = force_columns(g);
  std::vector<std::vector<std::byte>> out(gh.count.size());
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = gather(cols, RowRange{gh.first[r], gh.count[r]});
  const std::vector<std::vector<std::byte>> in = exchange_with_self(std::move(out), gh.peers, mpi);
  for (std::size_t r = 0; r < in.size(); ++r) scatter(cols, gh.send[r], in[r], true);
}

}  // namespace gf
