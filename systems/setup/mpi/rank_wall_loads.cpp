#include "systems/setup/mpi/rank_wall_loads.hpp"

#include <cstring>
#include <stdexcept>
#include <vector>

#include "systems/walls/mesh_wall_contact.hpp"

namespace gf {

namespace {

void add(WallLoad& l, const double* a) {
  const WallLoad x = wall_load_of(a);
  l.force = l.force + x.force;
  l.moment = l.moment + x.moment;
  l.power += x.power;
}

// Zero sums of this shape: the ranks but 0 continue from none.
WallLoads zeros_like(const WallLoads& l) {
  WallLoads z;
  z.now.resize(l.now.size());
  z.sum.resize(l.sum.size());
  z.steps = l.steps;
  return z;
}

}  // namespace

WallLoads gather_wall_loads(const WallLoads& mine, const MpiContext& mpi) {
  std::vector<double> v;
  for (const WallLoad& l : mine.now) append_wall_load(v, l);
  for (const WallLoad& l : mine.sum) append_wall_load(v, l);
  std::vector<std::byte> bytes(v.size() * sizeof(double));
  if (!v.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
  const std::vector<std::vector<std::byte>> all = mpi.gather(bytes, 0);
  if (mpi.rank() != 0) return mine;
  WallLoads total = zeros_like(mine);
  for (const std::vector<std::byte>& part : all) {
    // Every rank holds the same walls; a part of another size is a defect of the build, not of input.
    if (part.size() != bytes.size()) throw std::logic_error("a rank sent another number of wall loads");
    std::vector<double> r(v.size());
    if (!r.empty()) std::memcpy(r.data(), part.data(), part.size());
    for (std::size_t k = 0; k < total.now.size(); ++k) add(total.now[k], &r[kWallLoadNumbers * k]);
    const std::size_t base = kWallLoadNumbers * total.now.size();
    for (std::size_t k = 0; k < total.sum.size(); ++k) add(total.sum[k], &r[base + kWallLoadNumbers * k]);
  }
  return total;
}

void save_rank_wall_loads(CheckpointWriter& out, const World& w, const MpiContext& mpi) {
  const WallLoads& walls = w.resources.get<Walls>().loads;
  const MeshWallLoads* meshes = w.resources.find<MeshWallLoads>();
  save_wall_loads(out, "rank.walls.loads", walls);
  if (meshes) save_wall_loads(out, "rank.mesh_walls.loads", *meshes);
  const WallLoads all_walls = gather_wall_loads(walls, mpi);
  const WallLoads all_meshes = meshes ? gather_wall_loads(*meshes, mpi) : WallLoads{};
  if (mpi.rank() != 0) return;
  save_wall_loads(out, "rank.walls.loads_all", all_walls);
  if (meshes) save_wall_loads(out, "rank.mesh_walls.loads_all", all_meshes);
}

void restore_rank_wall_loads(const CheckpointReader& in, World& w) {
  restore_wall_loads(in, "rank.walls.loads", w.resources.get<Walls>().loads);
  if (MeshWallLoads* m = w.resources.find<MeshWallLoads>()) restore_wall_loads(in, "rank.mesh_walls.loads", *m);
}

void restore_rank_wall_loads_portable(const CheckpointReader& first, World& w, const MpiContext& mpi) {
  WallLoads& walls = w.resources.get<Walls>().loads;
  restore_wall_loads(first, "rank.walls.loads_all", walls);
  if (mpi.rank() != 0) walls = zeros_like(walls);
  if (MeshWallLoads* m = w.resources.find<MeshWallLoads>()) {
    restore_wall_loads(first, "rank.mesh_walls.loads_all", *m);
    if (mpi.rank() != 0) static_cast<WallLoads&>(*m) = zeros_like(*m);
  }
}

}  // namespace gf
