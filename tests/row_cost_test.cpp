// Row costs for balancing the ranks' boxes (systems/decomposition/row_cost.hpp): 1 a row plus the
// pair cost for each listed pair, halved between two owned rows, whole at the owned row of a pair
// with a ghost row; all ones without a list for these rows.
#include <catch2/catch.hpp>

#include "systems/decomposition/row_cost.hpp"

TEST_CASE("row costs share each listed pair between its owned rows and charge a ghost pair to its owned row") {
  gf::Grains g;
  g.resize(5);
  g.n_owned = 4;  // row 4 is a ghost
  gf::NeighborList list;
  // Pairs (0,1), (0,2), (1,4): the CSR rows of owners 0..3.
  list.offsets = {0, 2, 3, 3, 3};
  list.i = {0, 0, 1};
  list.j = {1, 2, 4};
  const double k = 0.4;
  const std::vector<double> c = gf::row_costs(g, list, k);
  REQUIRE(c.size() == 4);
  CHECK(c[0] == Approx(1.0 + k));        // half of (0,1) and of (0,2)
  CHECK(c[1] == Approx(1.0 + 1.5 * k));  // half of (0,1), all of (1,4)
  CHECK(c[2] == Approx(1.0 + 0.5 * k));
  CHECK(c[3] == 1.0);
  // The ranks' total: rows plus the pair cost of every listed pair.
  CHECK(c[0] + c[1] + c[2] + c[3] == Approx(4.0 + 3.0 * k));

  list.offsets = {0, 3};  // a list for other rows (before the first rebuild): unweighted
  for (const double x : gf::row_costs(g, list, k)) CHECK(x == 1.0);
  CHECK(gf::kPairCost == 0.46);
}
