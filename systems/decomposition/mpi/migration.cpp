#include "systems/decomposition/mpi/migration.hpp"

#include <stdexcept>

#include "systems/decomposition/row_bytes.hpp"

namespace gf {

std::vector<int> row_owners(const Grains& g, const Rcb& rcb) {
  std::vector<int> out(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i) out[i] = rcb.owner_of({g.pos.x[i], g.pos.y[i], g.pos.z[i]});
  return out;
}

MigrationCount migrate_rows(Grains& g, std::span<const int> owner, const MpiContext& mpi, const std::vector<int>* peers) {
  if (owner.size() != g.n_owned) throw std::invalid_argument("migrate_rows needs one owner per owned row");
  const auto ranks = static_cast<std::size_t>(mpi.size());
  std::vector<std::vector<std::uint32_t>> leaving(ranks);
  std::vector<std::uint32_t> keep;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const int r = owner[i];
    if (r < 0 || r >= mpi.size()) throw std::out_of_range("row owner outside the ranks");
    if (r == mpi.rank()) keep.push_back(static_cast<std::uint32_t>(i));
    else leaving[static_cast<std::size_t>(r)].push_back(static_cast<std::uint32_t>(i));
  }
  std::vector<std::vector<std::byte>> send(ranks);
  MigrationCount count;
  for (std::size_t r = 0; r < ranks; ++r) {
    pack_rows(g, leaving[r], send[r]);
    count.sent += leaving[r].size();
  }
  const std::vector<std::vector<std::byte>> recv = peers ? mpi.exchange(send, *peers) : mpi.exchange(send);
  std::vector<std::byte> arriving;
  for (const auto& bytes : recv) arriving.insert(arriving.end(), bytes.begin(), bytes.end());
  count.received = keep_and_append(g, keep, arriving);
  return count;
}

}  // namespace gf
