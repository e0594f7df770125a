// Shared by the tests run on several ranks: the communicator, and grains whose every column byte is
// a function of the grain's id, so a rank can check a row it received without seeing the sender's.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>

#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/decomposition/row_bytes.hpp"

namespace gf::test {

const MpiContext& test_world();

// Byte b of column c of the grain with this id.
inline std::byte id_byte(std::int64_t id, std::size_t c, std::size_t b) {
  std::uint64_t h = static_cast<std::uint64_t>(id) * 0x9E3779B97F4A7C15ull ^ (c * 0xBF58476D1CE4E5B9ull + b);
  h ^= h >> 31;
  h *= 0x94D049BB133111EBull;
  return static_cast<std::byte>(h >> 56);
}

// Fills every column of `row` from the id, then the id and the position.
inline void stamp_row(Grains& g, std::size_t row, std::int64_t id, const std::array<double, 3>& p) {
  const std::vector<RawColumn> cols = raw_row_columns(g);
  for (std::size_t c = 0; c < cols.size(); ++c)
    for (std::size_t b = 0; b < cols[c].elem_size; ++b)
      static_cast<std::byte*>(cols[c].data)[row * cols[c].elem_size + b] = id_byte(id, c, b);
  g.pid.id[row] = id;
  g.pos.x[row] = p[0], g.pos.y[row] = p[1], g.pos.z[row] = p[2];
}

// Whether every column of row a of g holds the bytes of row b of ref.
inline bool same_row(Grains& g, std::size_t a, Grains& ref, std::size_t b) {
  const std::vector<RawColumn> x = raw_row_columns(g), y = raw_row_columns(ref);
  if (x.size() != y.size()) return false;
  for (std::size_t c = 0; c < x.size(); ++c)
    if (x[c].elem_size != y[c].elem_size ||
        std::memcmp(static_cast<const std::byte*>(x[c].data) + a * x[c].elem_size,
                    static_cast<const std::byte*>(y[c].data) + b * y[c].elem_size, x[c].elem_size) != 0)
      return false;
  return true;
}

}  // namespace gf::test

#include <random>
#include <vector>

#include "systems/decomposition/rcb.hpp"

namespace gf::test {

// A block of nx x ny x nz grains of 1 mm on a jittered lattice 0.95 mm apart (neighbours overlap),
// with velocities and spins; everything a function of the seed, so every rank builds the same.
struct Lattice {
  std::vector<double> x, y, z, vx, vy, vz, wx, wy, wz;
  double radius = 0.5e-3;  // m
  DomainBox box;
  std::size_t size() const { return x.size(); }
};

inline Lattice make_lattice(int nx, int ny, int nz, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> jitter(-2e-5, 2e-5), v(-0.05, 0.05), w(-20.0, 20.0);
  Lattice l;
  const double a = 0.95e-3;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) {
        l.x.push_back(a * (i + 1) + jitter(rng));
        l.y.push_back(a * (j + 1) + jitter(rng));
        l.z.push_back(a * (k + 1) + jitter(rng));
        for (auto* c : {&l.vx, &l.vy, &l.vz}) c->push_back(v(rng));
        for (auto* c : {&l.wx, &l.wy, &l.wz}) c->push_back(w(rng));
      }
  l.box = {{0.0, 0.0, 0.0}, {a * (nx + 1), a * (ny + 1), a * (nz + 1)}};
  return l;
}

// The lattice's grains whose owner is `rank` (all of them for rank -1), as owned rows with id = index.
inline Grains lattice_grains(const Lattice& l, const Rcb& rcb, int rank) {
  Grains g;
  std::vector<std::size_t> mine;
  for (std::size_t k = 0; k < l.size(); ++k)
    if (rank < 0 || rcb.owner_of({l.x[k], l.y[k], l.z[k]}) == rank) mine.push_back(k);
  g.resize(mine.size());
  const double m = 2500.0 * 4.0 / 3.0 * 3.141592653589793 * l.radius * l.radius * l.radius;
  for (std::size_t r = 0; r < mine.size(); ++r) {
    const std::size_t k = mine[r];
    g.pos.x[r] = l.x[k], g.pos.y[r] = l.y[k], g.pos.z[r] = l.z[k];
    g.vel.x[r] = l.vx[k], g.vel.y[r] = l.vy[k], g.vel.z[r] = l.vz[k];
    g.omega.x[r] = l.wx[k], g.omega.y[r] = l.wy[k], g.omega.z[r] = l.wz[k];
    g.radius.r[r] = l.radius;
    g.mass.m[r] = m, g.mass.inv_m[r] = 1.0 / m, g.mass.inv_inertia[r] = 1.0 / (0.4 * m * l.radius * l.radius);
    g.species.type[r] = 0;
    g.pid.id[r] = static_cast<std::int64_t>(k);
  }
  return g;
}

inline Rcb lattice_split(const Lattice& l, int ranks) { return Rcb(l.box, l.x, l.y, l.z, {}, ranks); }

}  // namespace gf::test
