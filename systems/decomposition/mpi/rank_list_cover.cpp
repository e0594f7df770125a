#include "systems/decomposition/mpi/rank_list_cover.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace gf {

namespace {

// A mover in flight: where it is now, its radius and its id.
struct MoverRecord {
  double x, y, z, r;
  std::int64_t id;
};

std::vector<std::byte> pack_movers(const Grains& g, const std::vector<std::uint32_t>& rows) {
  std::vector<std::byte> out(rows.size() * sizeof(MoverRecord));
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::uint32_t i = rows[k];
    const MoverRecord m{g.pos.x[i], g.pos.y[i], g.pos.z[i], g.radius.r[i], g.pid.id[i]};
    std::memcpy(out.data() + k * sizeof m, &m, sizeof m);
  }
  return out;
}

void unpack_movers(const std::vector<std::byte>& bytes, int owner, std::vector<MoverPoint>& points) {
  if (bytes.size() % sizeof(MoverRecord) != 0) throw std::runtime_error("a movers message is not whole movers");
  for (std::size_t at = 0; at < bytes.size(); at += sizeof(MoverRecord)) {
    MoverRecord m;
    std::memcpy(&m, bytes.data() + at, sizeof m);
    points.push_back({m.x, m.y, m.z, m.r, m.id, 0, owner});
  }
}

}  // namespace

bool rank_list_covers(const Grains& g, BroadphaseState& s, const NeighborList& list, const MpiContext& mpi,
                      const std::vector<int>& peers) {
  // Collectives: the largest displacement (infinite where a list is invalid or a position is NaN:
  // no bound), the movers' excess over an eighth of the rows, the exchange, the verdict.
  const double* rx = s.ref_x.data();
  const double* ry = s.ref_y.data();
  const double* rz = s.ref_z.data();
  const bool valid = !list_invalid(g, s) && list.offsets.size() == g.n_owned + 1;
  double d2 = valid ? largest_displacement2(g, rx, ry, rz) : INFINITY;
  if (!(d2 <= INFINITY)) d2 = INFINITY;
  const double bound = mover_bound(s.skin, mpi.max(d2));
  if (!(bound > 0.0)) return false;
  collect_movers(g, rx, ry, rz, bound, g.n_owned, s.cover);
  const std::vector<std::uint32_t>& mine = s.cover.movers;
  const auto excess = 8 * static_cast<std::int64_t>(mine.size()) - static_cast<std::int64_t>(g.n_owned);
  if (mpi.sum(excess) > 0) return false;  // more movers than an eighth of all rows

  std::vector<std::vector<std::byte>> send(static_cast<std::size_t>(mpi.size()));
  const std::vector<std::byte> packed = pack_movers(g, mine);
  for (const int p : peers) send[static_cast<std::size_t>(p)] = packed;
  const std::vector<std::vector<std::byte>> in = mpi.exchange(send, peers);
  const int me = mpi.rank();
  std::vector<MoverPoint>& points = s.cover.points;
  points.clear();
  for (const std::uint32_t i : mine) points.push_back({g.pos.x[i], g.pos.y[i], g.pos.z[i], g.radius.r[i], g.pid.id[i], i, me});
  for (const int p : peers) unpack_movers(in[static_cast<std::size_t>(p)], p, points);

  const bool covered = each_touching_pair(points, s.reach, [&](const MoverPoint& a, const MoverPoint& b) {
    if (std::max(a.owner, b.owner) != me) return true;  // the higher owner looks it up
    const std::uint64_t key = pair_key(a.id, b.id);
    if (a.owner == b.owner) return listed_under(list, std::min(a.row, b.row), key);
    return listed_under(list, a.owner == me ? a.row : b.row, key);
  });
  return mpi.max(covered ? 0.0 : 1.0) == 0.0;
}

}  // namespace gf
