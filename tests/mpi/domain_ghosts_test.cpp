// Ghost rows on two ranks (or more): each rank holds, after its owned rows, exactly the other rank's grains
// within reach of its box, with the owner's columns; after the owners move their grains, a refresh
// brings the ghosts' positions, velocities and spins to the owners' values.
#include <catch2/catch.hpp>

#include <algorithm>
#include <vector>

#include "systems/decomposition/mpi/domain_ghosts.hpp"
#include "tests/mpi/mpi_test_support.hpp"

namespace {

constexpr double kSkin = 1.5e-4;  // m

// Ids of the lattice's grains owned by another rank within reach of this rank's box, by owner and
// then id (the owners' row order).
std::vector<std::int64_t> expected_ghosts(const gf::test::Lattice& l, const gf::Rcb& rcb, int rank, double reach,
                                          gf::GhostShell shell) {
  std::vector<std::int64_t> out;
  for (int from = 0; from < rcb.ranks(); ++from) {
    if (from == rank || (shell == gf::GhostShell::half && from > rank)) continue;
    for (std::size_t k = 0; k < l.size(); ++k)
      if (rcb.owner_of({l.x[k], l.y[k], l.z[k]}) == from && rcb.box(rank).distance({l.x[k], l.y[k], l.z[k]}) <= reach)
        out.push_back(static_cast<std::int64_t>(k));
  }
  return out;
}

// The owners' motion between two refreshes: a shift, velocity and spin change by id.
void move_owned(gf::Grains& g) {
  for (std::size_t r = 0; r < g.n_owned; ++r) {
    const double s = 1e-6 * static_cast<double>(g.pid.id[r] % 7);
    g.pos.x[r] += s, g.pos.y[r] -= s, g.pos.z[r] += 2 * s;
    g.vel.x[r] += s, g.omega.z[r] -= s;
  }
}

}  // namespace

TEST_CASE("ghost rows hold the neighbour's grains within reach and follow their owners", "[mpi][ghosts]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  const gf::GhostShell shell = GENERATE(gf::GhostShell::full, gf::GhostShell::half);
  const gf::test::Lattice l = gf::test::make_lattice(12, 5, 5, 21);
  const gf::Rcb rcb = gf::test::lattice_split(l, mpi.size());
  gf::Grains g = gf::test::lattice_grains(l, rcb, mpi.rank());
  gf::Grains all = gf::test::lattice_grains(l, rcb, -1);
  const double reach = 2.0 * l.radius + kSkin;
  gf::DomainGhosts gh;
  gf::make_domain_ghosts(g, rcb, reach, mpi, gh, shell);
  CHECK(mpi.sum(static_cast<std::int64_t>(g.n_owned)) == static_cast<std::int64_t>(l.size()));
  CHECK(g.n == g.n_owned + gh.size());
  const std::vector<std::int64_t> want = expected_ghosts(l, rcb, mpi.rank(), reach, shell);
  std::vector<std::int64_t> got(g.pid.id.begin() + static_cast<std::ptrdiff_t>(g.n_owned), g.pid.id.end());
  CHECK(got == want);
  CHECK(mpi.sum(static_cast<std::int64_t>(want.size())) > 0);
  // A ghost row holds its owner's core columns (the full table holds row k as id k).
  for (std::size_t r = g.n_owned; r < g.n; ++r) {
    const auto k = static_cast<std::size_t>(g.pid.id[r]);
    CHECK(g.pos.x[r] == all.pos.x[k]);
    CHECK(g.omega.y[r] == all.omega.y[k]);
    CHECK(g.radius.r[r] == all.radius.r[k]);
    CHECK(g.mass.inv_inertia[r] == all.mass.inv_inertia[k]);
  }
  // The owners move; after a refresh the ghosts are where their owners are.
  move_owned(g);
  move_owned(all);
  gf::refresh_domain_ghosts(g, gh, mpi);
  std::size_t equal = 0;
  for (std::size_t r = g.n_owned; r < g.n; ++r) {
    const auto k = static_cast<std::size_t>(g.pid.id[r]);
    equal += g.pos.x[r] == all.pos.x[k] && g.pos.y[r] == all.pos.y[k] && g.pos.z[r] == all.pos.z[k] &&
             g.vel.x[r] == all.vel.x[k] && g.omega.z[r] == all.omega.z[k];
  }
  CHECK(equal == g.n - g.n_owned);
}
