// The Grains table: soft spheres. Rows [0, n_owned) are owned; ghost and periodic-image rows,
// when domain decomposition arrives, follow them and are read but never written by kernels.
// Later archetypes (Bodies with their Members, FluidNodes) are tables of their own beside this one.
#pragma once

#include <cstdint>
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

struct Grains {
  std::size_t n_owned = 0;
  std::size_t n = 0;  // owned + ghosts

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

  template <class F>
  void for_each_core_column(F&& f) {
    std::apply([&](auto&... comp) { (for_each_column(comp, f), ...); }, components());
  }

  void resize(std::size_t rows) {
    for_each_core_column([rows](auto& col) { col.resize(rows); });
    extras.resize(rows);
    n = n_owned = rows;
  }

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
