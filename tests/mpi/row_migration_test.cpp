// Row migration on two ranks: grains placed across the cut go to the other rank with every column
// byte-identical (the spins, and the attached wall springs and mesh slots), keep their ids and
// follow the rows that stayed; the total row count is conserved.
#include <catch2/catch.hpp>

#include <vector>

#include "systems/decomposition/mpi/migration.hpp"
#include "systems/walls/mesh_wall_contact.hpp"
#include "systems/walls/walls.hpp"
#include "tests/mpi/mpi_test_support.hpp"

namespace {

const gf::DomainBox kDomain{{0.0, 0.0, 0.0}, {1.0, 0.5, 0.5}};

// Two ranks: cut at x = 0.5, from a lattice both ranks build alike.
gf::Rcb two_halves() {
  std::vector<double> x, y, z;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 5; ++j) {
      x.push_back(0.05 + 0.1 * i);
      y.push_back(0.05 + 0.1 * j);
      z.push_back(0.25);
    }
  return gf::Rcb(kDomain, x, y, z, {}, 2);
}

// Rank 0 holds ids 0..9 on its side but id 3 past the cut; rank 1 ids 100..109, id 105 on rank 0's side.
std::array<double, 3> place(std::int64_t id) {
  const bool first = id < 100;
  const auto k = static_cast<double>(id % 100);
  const bool crossed = id == 3 || id == 105;
  const double x = (first != crossed) ? 0.1 + 0.03 * k : 0.6 + 0.03 * k;
  return {x, 0.1 + 0.01 * k, 0.2};
}

void attach_histories(gf::Grains& g, std::size_t rows) {
  g.extras.attach<gf::WallHistory>(rows).shape(2, rows);
  g.extras.attach<gf::MeshContactHistory>(rows);
}

gf::Grains make_table(int rank, bool spin) {
  gf::Grains g;
  g.spin = spin;
  g.resize(10);
  attach_histories(g, 10);
  for (std::size_t r = 0; r < 10; ++r) {
    const std::int64_t id = (rank == 0 ? 0 : 100) + static_cast<std::int64_t>(r);
    gf::test::stamp_row(g, r, id, place(id));
  }
  return g;
}

}  // namespace

TEST_CASE("rows crossing the cut arrive on the other rank byte-identical", "[mpi][migration]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() == 2);
  const bool spin = GENERATE(true, false);
  gf::Grains g = make_table(mpi.rank(), spin);
  const std::size_t bytes_per_row = gf::row_bytes(g);
  const gf::Rcb rcb = two_halves();
  const gf::MigrationCount moved = gf::migrate_rows(g, gf::row_owners(g, rcb), mpi);
  CHECK(moved.sent == 1);
  CHECK(moved.received == 1);
  CHECK(mpi.sum(static_cast<std::int64_t>(g.n_owned)) == 20);
  CHECK(g.n == g.n_owned);
  // The rows that stayed, in their order, then the one that arrived.
  std::vector<std::int64_t> expected;
  for (std::int64_t k = 0; k < 10; ++k)
    if (k != (mpi.rank() == 0 ? 3 : 5)) expected.push_back((mpi.rank() == 0 ? 0 : 100) + k);
  expected.push_back(mpi.rank() == 0 ? 105 : 3);
  std::vector<std::int64_t> ids(g.pid.id.begin(), g.pid.id.end());
  CHECK(ids == expected);
  // Every column of every row, the arrived one included, as the grain's id made it.
  gf::Grains ref;
  ref.spin = spin;
  ref.resize(1);
  attach_histories(ref, 1);
  CHECK(gf::row_bytes(ref) == bytes_per_row);
  for (std::size_t r = 0; r < g.n_owned; ++r) {
    gf::test::stamp_row(ref, 0, g.pid.id[r], place(g.pid.id[r]));
    INFO("rank " << mpi.rank() << ", id " << g.pid.id[r]);
    CHECK(gf::test::same_row(g, r, ref, 0));
    CHECK(rcb.owner_of({g.pos.x[r], g.pos.y[r], g.pos.z[r]}) == mpi.rank());
  }
}

TEST_CASE("a migration with nothing to move leaves the table as it was", "[mpi][migration]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  gf::Grains g = make_table(mpi.rank(), true);
  std::vector<int> stay(g.n_owned, mpi.rank());
  const gf::MigrationCount moved = gf::migrate_rows(g, stay, mpi);
  CHECK(moved.sent == 0);
  CHECK(moved.received == 0);
  gf::Grains ref = make_table(mpi.rank(), true);
  for (std::size_t r = 0; r < g.n_owned; ++r) CHECK(gf::test::same_row(g, r, ref, r));
}
