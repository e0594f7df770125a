// The contacts of composite bodies shared out among ranks (body_contact_split.hpp) against the same
// scene stepped by one process in this one (DemSimulation without a split): after thousands of steps
// of a pour onto a closed hopper gate, with pair and wall springs carried the whole way, every
// column of the bodies and every spring must be byte-equal. That is the claim of the split: each
// outcome is computed by the same code on the same state, and every rank adds them in one
// process's order, so no tolerance is needed (a lost outcome, a spring written to the wrong member
// or a sum in another order shows in the last bits at once and grows from there).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "engine/table.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "app/mpi/rank_body_app.hpp"
#include "tests/mpi/mpi_test_support.hpp"

namespace {

// The mixed hopper (prisms, spheres of one member, three fixed boxes, plane walls) with fewer
// bodies: poured onto the closed gate for 0.4 s (settling), then the gate is taken away.
gf::DemSimulation hopper() {
  return gf::DemSimulation::from_file(std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/hopper_mixed_prisms_spheres.toml",
                                      {"bodies.2.count=60", "fill.0.count.glass=30", "settle.time=0.4", "run.dt=4e-5"});
}

void install_split(gf::World& world, const gf::MpiContext& mpi, std::size_t& shares) {
  // grainflow_mpi's split, its exchanges counted.
  gf::BodyContactSplit split = gf::rank_contact_split(mpi);
  split.share = [share = split.share, &shares](std::vector<std::byte> mine) {
    ++shares;
    return share(std::move(mine));
  };
  world.resources.emplace<gf::BodyContactSplit>(std::move(split));
}

template <class C>
bool same_bytes(const C& a, const C& b) {
  return a.size() == b.size() && (a.size() == 0 || std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0);
}

// Every column of the two tables' components, byte for byte; the names of those that differ.
std::string differing_columns(gf::Bodies& a, gf::Bodies& b) {
  std::vector<const void*> left;
  std::vector<std::size_t> sizes;
  std::apply([&](auto&... comp) { (gf::for_each_column(comp, [&](auto& col) {
                                     left.push_back(col.data());
                                     sizes.push_back(col.size() * sizeof(col[0]));
                                   }), ...); },
             a.components());
  std::string out;
  std::size_t k = 0;
  std::apply([&](auto&... comp) { (gf::for_each_column(comp, [&](auto& col) {
                                     if (col.size() * sizeof(col[0]) != sizes[k] ||
                                         std::memcmp(col.data(), left[k], sizes[k]) != 0)
                                       out += " column " + std::to_string(k);
                                     ++k;
                                   }), ...); },
             b.components());
  return out;
}

}  // namespace

TEST_CASE("composite bodies with their contacts shared among ranks step byte for byte as one process") {
  const gf::MpiContext& mpi = gf::test::test_world();
  gf::DemSimulation one = hopper(), shared = hopper();
  std::size_t shares = 0;
  install_split(shared.world(), mpi, shares);
  const gf::BodyContactState& a = one.world().resources.get<gf::BodyContactState>();
  const gf::BodyContactState& b = shared.world().resources.get<gf::BodyContactState>();
  const std::int64_t settle = 10000, chunk = 500, steps = 2500;  // 0.4 s and 0.1 s at 4e-5 s
  one.settle();
  shared.settle();
  std::size_t most_pairs = a.last.pair_contacts, most_walls = a.last.wall_contacts;  // touching, after each chunk
  for (std::int64_t k = 0; k < steps; k += chunk) {
    one.advance(chunk);
    shared.advance(chunk);
    most_pairs = std::max(most_pairs, a.last.pair_contacts);
    most_walls = std::max(most_walls, a.last.wall_contacts);
  }
  CHECK(shares == static_cast<std::size_t>(settle + steps) + 1);  // the priming pass and every step
  INFO("rank " << mpi.rank() << " of " << mpi.size() << ": up to " << most_pairs << " member pairs and " << most_walls
               << " walls touching; at the end " << a.list.pairs() << " listed, " << a.rebuilds << " rebuilds");
  // Not vacuous: pairs and walls touched on the way, and every rank has listed pairs of its own.
  REQUIRE(most_pairs >= 8);
  REQUIRE(most_walls >= 10);
  REQUIRE(a.rebuilds >= 3);
  CHECK(gf::split_blocks(gf::rank_contact_split(mpi)).count(a.list.pairs()) > 0);

  CHECK(differing_columns(one.world().tables.get<gf::Bodies>(), shared.world().tables.get<gf::Bodies>()).empty());
  CHECK(b.last.pair_contacts == a.last.pair_contacts);
  CHECK(b.last.wall_contacts == a.last.wall_contacts);
  CHECK(b.last.max_overlap == a.last.max_overlap);
  CHECK(same_bytes(b.list.key, a.list.key));
  CHECK(same_bytes(b.history.pair, a.history.pair));
  for (std::size_t q = 0; q < a.history.width; ++q) CHECK(same_bytes(b.history.value[q], a.history.value[q]));
  CHECK(same_bytes(b.walls.value, a.walls.value));
  CHECK(same_bytes(b.walls.touching, a.walls.touching));
}

TEST_CASE("the ranks' shares of a split cover every item once") {
  for (int ranks : {1, 2, 3, 5})
    for (std::size_t n : {0u, 1u, 2u, 7u, 1000u}) {
      std::vector<int> owners(n, 0);
      for (int r = 0; r < ranks; ++r) {
        gf::BodyContactSplit s;
        s.rank = r, s.ranks = ranks;
        const gf::SplitBlocks b = gf::split_blocks(s);
        for (std::size_t j = 0; j < b.count(n); ++j) {
          REQUIRE(b.item(j) < n);
          CHECK(b.mine(b.item(j)));
          ++owners[b.item(j)];
        }
      }
      CHECK(std::count(owners.begin(), owners.end(), 1) == static_cast<std::ptrdiff_t>(n));
    }
  gf::BodyContactSplit bad;
  bad.rank = 2, bad.ranks = 2;
  CHECK_THROWS_AS(gf::split_blocks(bad), std::invalid_argument);
}

TEST_CASE("ranks whose bodies' states differ stop together at the next step") {
  const gf::MpiContext& mpi = gf::test::test_world();
  gf::DemSimulation sim = hopper();
  std::size_t shares = 0;
  install_split(sim.world(), mpi, shares);
  sim.advance(10);
  // The last rank's first body one unit in the last place higher, as a machine that rounds
  // differently would leave it.
  if (mpi.rank() == mpi.size() - 1) {
    gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
    b.pos.y[0] = std::nextafter(b.pos.y[0], 1.0);
  }
  CHECK_THROWS_WITH(sim.advance(1), Catch::Contains("hold different states"));
}
