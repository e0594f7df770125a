#include "systems/setup/mpi/gathered_grains.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace gf {

namespace {

struct ShapeRecord {
  std::int64_t id = 0;
  std::int32_t type = 0, unused = 0;
  double x[3] = {}, r = 0, v[3] = {};
};

struct StateRecord {
  std::int64_t id = 0;
  std::int32_t type = 0, unused = 0;
  double x[3] = {}, v[3] = {}, w[3] = {};
  double d = 0;  // m
};

// Every rank's records on rank 0, sorted by id; empty elsewhere.
template <class T>
std::vector<T> gather_by_id(const std::vector<T>& mine, const MpiContext& mpi) {
  static_assert(std::is_trivially_copyable_v<T>);
  std::vector<std::byte> bytes(mine.size() * sizeof(T));
  if (!bytes.empty()) std::memcpy(bytes.data(), mine.data(), bytes.size());
  std::vector<T> all;
  for (const std::vector<std::byte>& part : mpi.gather(bytes, 0)) {
    if (part.size() % sizeof(T) != 0) throw std::runtime_error("a gathered message is not whole grain records");
    const std::size_t at = all.size();
    all.resize(at + part.size() / sizeof(T));
    if (!part.empty()) std::memcpy(static_cast<void*>(all.data() + at), part.data(), part.size());
  }
  std::sort(all.begin(), all.end(), [](const T& a, const T& b) { return a.id < b.id; });
  return all;
}

}  // namespace

Grains gather_shapes(const Grains& g, const MpiContext& mpi) {
  std::vector<ShapeRecord> mine(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i)
    mine[i] = {g.pid.id[i], g.species.type[i], 0, {g.pos.x[i], g.pos.y[i], g.pos.z[i]}, g.radius.r[i],
               {g.vel.x[i], g.vel.y[i], g.vel.z[i]}};
  const std::vector<ShapeRecord> all = gather_by_id(mine, mpi);
  Grains out;
  out.spin = false;
  out.resize(all.size());
  for (std::size_t i = 0; i < all.size(); ++i) {
    out.pid.id[i] = all[i].id;
    out.species.type[i] = all[i].type;
    out.pos.x[i] = all[i].x[0], out.pos.y[i] = all[i].x[1], out.pos.z[i] = all[i].x[2];
    out.radius.r[i] = all[i].r;
    out.vel.x[i] = all[i].v[0], out.vel.y[i] = all[i].v[1], out.vel.z[i] = all[i].v[2];
  }
  return out;
}

std::vector<StateRow> gather_state_rows(const Grains& g, const MpiContext& mpi) {
  std::vector<StateRecord> mine(g.n_owned);
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    StateRecord& r = mine[i];
    r.id = g.pid.id[i];
    r.type = g.species.type[i];
    r.d = 2.0 * g.radius.r[i];
    r.x[0] = g.pos.x[i], r.x[1] = g.pos.y[i], r.x[2] = g.pos.z[i];
    r.v[0] = g.vel.x[i], r.v[1] = g.vel.y[i], r.v[2] = g.vel.z[i];
    if (g.spin) r.w[0] = g.omega.x[i], r.w[1] = g.omega.y[i], r.w[2] = g.omega.z[i];
  }
  std::vector<StateRow> rows;
  for (const StateRecord& r : gather_by_id(mine, mpi))
    rows.push_back({r.id, r.type + 1, r.d,
                    {r.x[0], r.x[1], r.x[2]}, 0, {r.v[0], r.v[1], r.v[2]}, {r.w[0], r.w[1], r.w[2]}});
  return rows;
}

}  // namespace gf
