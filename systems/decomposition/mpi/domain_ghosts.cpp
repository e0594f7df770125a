#include "systems/decomposition/mpi/domain_ghosts.hpp"

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

// The values of the given columns at rows first + k, row after row, as bytes.
template <class Rows>
std::vector<std::byte> gather(const std::vector<ColumnD*>& cols, const Rows& rows) {
  std::vector<double> v;
  v.reserve(rows.size() * cols.size());
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (const ColumnD* c : cols) v.push_back((*c)[rows[k]]);
  std::vector<std::byte> out(v.size() * sizeof(double));
  if (!v.empty()) std::memcpy(out.data(), v.data(), out.size());
  return out;
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
                        GhostShell shell) {
  if (rcb.ranks() != mpi.size()) throw std::invalid_argument("the decomposition has another number of ranks");
  g.set_ghosts(0);
  const auto ranks = static_cast<std::size_t>(mpi.size());
  gh.send.assign(ranks, {});
  gh.peers = box_peers(rcb, mpi.rank(), reach);
  std::vector<std::vector<std::byte>> out(ranks);
  for (const int r : gh.peers) {
    if (shell == GhostShell::half && r < mpi.rank()) continue;
    auto& rows = gh.send[static_cast<std::size_t>(r)];
    for (std::size_t i = 0; i < g.n_owned; ++i)
      if (rcb.box(r).distance({g.pos.x[i], g.pos.y[i], g.pos.z[i]}) <= reach) rows.push_back(static_cast<std::uint32_t>(i));
    pack_rows(g, rows, out[static_cast<std::size_t>(r)], true);
  }
  const std::vector<std::vector<std::byte>> in = mpi.exchange(out, gh.peers);
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
}

void refresh_domain_ghosts(Grains& g, const DomainGhosts& gh, const MpiContext& mpi) {
  const std::vector<ColumnD*> cols = state_columns(g);
  std::vector<std::vector<std::byte>> out(gh.send.size());
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = gather(cols, gh.send[r]);
  const std::vector<std::vector<std::byte>> in = mpi.exchange(out, gh.peers);
  for (std::size_t r = 0; r < in.size(); ++r) scatter(cols, RowRange{gh.first[r], gh.count[r]}, in[r], false);
}

void fold_domain_ghost_forces(Grains& g, const DomainGhosts& gh, const MpiContext& mpi) {
  const std::vector<ColumnD*> cols = force_columns(g);
  std::vector<std::vector<std::byte>> out(gh.count.size());
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = gather(cols, RowRange{gh.first[r], gh.count[r]});
  const std::vector<std::vector<std::byte>> in = mpi.exchange(out, gh.peers);
  for (std::size_t r = 0; r < in.size(); ++r) scatter(cols, gh.send[r], in[r], true);
}

}  // namespace gf
