// The Grains table: soft spheres. Rows [0, n_owned) are owned; ghost rows follow them: the images of
// periodic boundaries (systems/periodic/), and later another domain's grains. Kernels read ghost rows;
// the pair contacts leave the partner side of a contact in its Force and Torque, which are summed into
// the owner's (periodic_images.hpp); nothing integrates them.
// Later archetypes (Bodies with their Members, FluidNodes) are tables of their own beside this one.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>
#include <tuple>
#include <type_traits>

#include "engine/column.hpp"
#include "engine/table.hpp"

namespace gf {

struct Position {
  ColumnD x, y, z;  // m
  auto columns() { return std::tie(x, y, z); }
};
struct Velocity {
  ColumnD x, y, z;  // m/s
  auto columns() { return std::tie(x, y, z); }
};
struct AngularVelocity {
  ColumnD x, y, z;  // rad/s
  auto columns() { return std::tie(x, y, z); }
};
struct Force {
  ColumnD x, y, z;  // N, from particle-particle contacts
  auto columns() { return std::tie(x, y, z); }
};
struct Torque {
  ColumnD x, y, z;  // N m, from particle-particle contacts
  auto columns() { return std::tie(x, y, z); }
};
struct WallForce {
  ColumnD x, y, z;  // N, from walls and other geometry
  auto columns() { return std::tie(x, y, z); }
};
struct WallTorque {
  ColumnD x, y, z;  // N m, from walls and other geometry
  auto columns() { return std::tie(x, y, z); }
};
struct Radius {
  ColumnD r;  // m
  auto columns() { return std::tie(r); }
};
struct Mass {
  ColumnD m;          // kg
  ColumnD inv_m;      // 1/kg
  ColumnD inv_inertia;  // 1/(kg m^2), solid sphere I = 2/5 m r^2
  auto columns() { return std::tie(m, inv_m, inv_inertia); }
};
struct Species {
  Column<std::int32_t> type;  // index into the scene's species list
  auto columns() { return std::tie(type); }
};
struct ParticleId {
  Column<std::int64_t> id;  // stable across re-sorting; keys contact history
  auto columns() { return std::tie(id); }
};

// One grain's state, for a row queued for insertion (Grains::queue_insert).
struct GrainRow {
  double x[3] = {}, v[3] = {}, w[3] = {};  // m, m/s, rad/s
  double radius = 0, mass = 0, inv_inertia = 0;  // m, kg, 1/(kg m^2)
  std::int32_t type = 0;
  std::int32_t unused = 0;  // explicit padding: checkpoints copy the bytes
  std::int64_t id = -1;     // given by queue_insert
};

// Rows to insert and ids to remove, applied together at the next neighbour-list rebuild (the only
// point where rows move), so kernels never see a table change under them mid-step.
struct RowChanges {
  std::vector<GrainRow> insert;
  std::vector<std::int64_t> remove;
  bool empty() const { return insert.empty() && remove.empty(); }
};

// The spin components: a table whose grains do not rotate (Grains::spin false) has none of them.
template <class C>
inline constexpr bool is_spin_component =
    std::is_same_v<C, AngularVelocity> || std::is_same_v<C, Torque> || std::is_same_v<C, WallTorque>;

struct Grains {
  static constexpr std::string_view kName = "grains";
  std::size_t n_owned = 0;
  std::size_t n = 0;  // owned + ghosts
  // Whether any grain rotates. Without rotation the spin components hold no rows at all (set before
  // the first resize); kernels then take spins as zero and write no torques.
  bool spin = true;
  // The next id queue_insert hands out; ids are never reused (checkpointed with the table).
  std::int64_t next_id = 0;
  RowChanges pending;

  Position pos;
  Velocity vel;
  AngularVelocity omega;
  Force force;
  Torque torque;
  WallForce wall_force;
  WallTorque wall_torque;
  Radius radius;
  Mass mass;
  Species species;
  ParticleId pid;
  ExtraComponents extras;

  auto components() {
    return std::tie(pos, vel, omega, force, torque, wall_force, wall_torque, radius, mass, species, pid);
  }

  // Every column the table holds (without rotation, not the spin components).
  template <class F>
  void for_each_core_column(F&& f) {
    auto visit = [&](auto& comp) {
      if (spin || !is_spin_component<std::decay_t<decltype(comp)>>) for_each_column(comp, f);
    };
    std::apply([&](auto&... comp) { (visit(comp), ...); }, components());
  }

  void resize(std::size_t rows) {
    for_each_core_column([rows](auto& col) { col.resize(rows); });
    extras.resize(rows);
    n = n_owned = rows;
  }
  // Room for `ghosts` rows after the owned ones (their contents are the exchange's to fill).
  void set_ghosts(std::size_t ghosts) {
    const std::size_t owned = n_owned;
    for_each_core_column([&](auto& col) { col.resize(owned + ghosts); });
    extras.resize(owned + ghosts);
    n = owned + ghosts;
  }
  std::size_t owned_rows() const { return n_owned; }
  std::size_t rows() const { return n; }

  // Queues a new grain (its id is returned, unique for the run) or the removal of one by id.
  std::int64_t queue_insert(GrainRow row);
  void queue_remove(std::int64_t id) { pending.remove.push_back(id); }
  // Applies the queued changes as one reorder: removed rows leave, the others keep their order,
  // new rows follow with zero forces and zero attached columns (contact history); ghost rows are
  // dropped (the exchange refills them). Returns, per old row, its new row or -1 if removed.
  // Unknown ids in the removal queue throw std::invalid_argument naming them.
  std::vector<std::int64_t> apply_pending();

  // New row r takes old row perm[r], in every core and attached column.
  void permute(std::span<const std::uint32_t> perm);

  std::size_t bytes();
};

// A component of the grains by type: a core member, or one a system attached.
template <class C, class Tuple>
inline constexpr bool is_core_component = false;
template <class C, class... T>
inline constexpr bool is_core_component<C, std::tuple<T...>> = (std::is_same_v<C&, T> || ...);

template <class C>
C& component(Grains& g) {
  if constexpr (is_core_component<C, decltype(g.components())>)
    return std::get<C&>(g.components());
  else
    return g.extras.get<C>();
}

}  // namespace gf
