// Forces across the cuts: a block of touching grains split between two ranks or more (ghost rows
// from lower ranks only, so each pair across a cut is evaluated once, on the higher rank, and its
// partner side is folded back to the owner) gets the forces and torques of the same block on one
// rank, to rounding. Run by ctest on two and on three ranks.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "systems/contact/linear_spring_dashpot.hpp"
#include "systems/contact/pair_contact.hpp"
#include "systems/decomposition/mpi/domain_ghosts.hpp"
#include "systems/periodic/periodic_images.hpp"
#include "tests/mpi/mpi_test_support.hpp"

namespace {

using Law = gf::LinearSpringDashpot;
constexpr double kSkin = 1.5e-4;  // m
constexpr double kDt = 1e-5;      // s

gf::ContactTable seed000_table(const gf::test::Lattice& l) {
  gf::ContactBody<Law::Material> body;
  body.radius = l.radius;
  body.mass = 2500.0 * 4.0 / 3.0 * 3.141592653589793 * std::pow(l.radius, 3);
  body.inertia = 0.4 * body.mass * l.radius * l.radius;
  const Law::Params p{1000.0, 600.0, 1e-5, 0.3, 0.3, 0.3, 0.3, 5e-5};
  return gf::make_contact_table<Law>({body}, {"small"}, {p}, {p});
}

// Every pair (owned row i, row j > i) within r_i + r_j + skin, by owner row then partner row.
gf::NeighborList all_pairs(const gf::Grains& g) {
  gf::NeighborList list;
  list.offsets.assign(g.n_owned + 1, 0);
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    for (std::size_t j = i + 1; j < g.n; ++j) {
      const double dx = g.pos.x[i] - g.pos.x[j], dy = g.pos.y[i] - g.pos.y[j], dz = g.pos.z[i] - g.pos.z[j];
      const double reach = g.radius.r[i] + g.radius.r[j] + kSkin;
      if (dx * dx + dy * dy + dz * dz > reach * reach) continue;
      list.i.push_back(static_cast<std::uint32_t>(i));
      list.j.push_back(static_cast<std::uint32_t>(j));
      list.key.push_back(gf::pair_key(g.pid.id[i], g.pid.id[j]));
    }
    list.offsets[i + 1] = static_cast<std::uint32_t>(list.i.size());
  }
  list.i_lane.assign(list.pairs(), 0);
  list.j_lane.assign(list.pairs(), 0);
  list.type_pair.assign(list.pairs(), 0);
  for (std::size_t k = 0; k < list.pairs(); ++k) {
    list.i_lane[k] = static_cast<std::int32_t>(list.i[k]);
    list.j_lane[k] = static_cast<std::int32_t>(list.j[k]);
  }
  return list;
}

// Evaluates the pair forces of g's list once, from fresh springs.
void pair_forces(gf::Grains& g, const gf::ContactTable& table) {
  const gf::NeighborList list = all_pairs(g);
  gf::PairHistory history;
  gf::set_layout(history, Law::history());
  history.slot.assign(list.pairs(), -1);
  gf::PairForces out;
  gf::compute_pair_forces<Law>(g, list, history, table, kDt, out);
}

// The largest difference (of the largest component) between each owned row's force and torque and
// those of the same grain in `one` (row = id); prints the counts and returns the difference over all ranks.
double compare_with_one(gf::Grains& one, gf::Grains& g, const gf::Rcb& rcb, const gf::DomainGhosts& gh, double reach,
                        const gf::MpiContext& mpi, const char* what) {
  double fmax = 0.0, tmax = 0.0;
  for (std::size_t k = 0; k < one.n_owned; ++k)
    for (int d = 0; d < 3; ++d) {
      fmax = std::max(fmax, std::abs((d == 0 ? one.force.x : d == 1 ? one.force.y : one.force.z)[k]));
      tmax = std::max(tmax, std::abs((d == 0 ? one.torque.x : d == 1 ? one.torque.y : one.torque.z)[k]));
    }
  REQUIRE(fmax > 0.0);
  REQUIRE(tmax > 0.0);
  double worst_f = 0.0, worst_t = 0.0;
  std::int64_t identical = 0, boundary = 0;
  for (std::size_t r = 0; r < g.n_owned; ++r) {
    const auto k = static_cast<std::size_t>(g.pid.id[r]);
    const double f[6] = {g.force.x[r], g.force.y[r], g.force.z[r], g.torque.x[r], g.torque.y[r], g.torque.z[r]};
    const double e[6] = {one.force.x[k], one.force.y[k], one.force.z[k], one.torque.x[k], one.torque.y[k], one.torque.z[k]};
    bool same = true;
    for (int c = 0; c < 6; ++c) {
      (c < 3 ? worst_f : worst_t) = std::max(c < 3 ? worst_f : worst_t, std::abs(f[c] - e[c]) / (c < 3 ? fmax : tmax));
      same = same && f[c] == e[c];
    }
    identical += same;
    for (int other = 0; other < mpi.size(); ++other)
      if (other != mpi.rank() && rcb.box(other).distance({g.pos.x[r], g.pos.y[r], g.pos.z[r]}) <= reach) {
        ++boundary;
        break;
      }
  }
  CHECK(mpi.sum(static_cast<std::int64_t>(gh.size())) > 0);
  const double worst = mpi.max(std::max(worst_f, worst_t));
  const std::int64_t same_all = mpi.sum(identical), boundary_all = mpi.sum(boundary);
  if (mpi.rank() == 0)
    std::cout << what << ": ranks " << mpi.size() << ", grains " << one.n_owned << ", at a cut " << boundary_all
              << ", bit-identical to one rank " << same_all << ", largest difference " << worst
              << " of the largest component\n";
  return worst;
}

}  // namespace

TEST_CASE("forces on grains split across ranks equal the one-rank forces to rounding", "[mpi][ghosts]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  const gf::test::Lattice l = gf::test::make_lattice(12, 5, 5, 5);
  const gf::Rcb rcb = gf::test::lattice_split(l, mpi.size());
  const gf::ContactTable table = seed000_table(l);
  gf::Grains one = gf::test::lattice_grains(l, rcb, -1);  // the whole block, row k = id k
  pair_forces(one, table);
  gf::Grains g = gf::test::lattice_grains(l, rcb, mpi.rank());
  gf::DomainGhosts gh;
  const double reach = 2.0 * l.radius + kSkin;
  gf::make_domain_ghosts(g, rcb, reach, mpi, gh, gf::GhostShell::half);
  pair_forces(g, table);
  gf::fold_domain_ghost_forces(g, gh, mpi);
  CHECK(compare_with_one(one, g, rcb, gh, reach, mpi, "block") <= 1e-12);
}

// The block made periodic along x and y, its faces one lattice spacing beyond the outer grains, so
// the grains across each face overlap as inside the block: the cuts along x then also meet across the
// face (rank 0's first grains touch the last rank's last), and each rank holds its own images across
// the y faces. The one-rank reference lists the pairs with periodic images (periodic_images.hpp).
TEST_CASE("forces across periodic faces split across ranks equal the one-rank forces to rounding",
          "[mpi][ghosts][periodic]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  REQUIRE(mpi.size() >= 2);
  gf::test::Lattice l = gf::test::make_lattice(12, 6, 5, 5);
  const double a = 0.95e-3;
  gf::PeriodicBox box;
  box.on = {true, true, false};
  box.lo = {0.5 * a, 0.5 * a, 0.0};
  box.hi = {12.5 * a, 6.5 * a, 0.0};
  for (std::size_t d = 0; d < 2; ++d) {  // the ranks' boxes tile the periodic box along x and y
    l.box.lo[d] = box.lo[d];
    l.box.hi[d] = box.hi[d];
  }
  const gf::Rcb rcb = gf::test::lattice_split(l, mpi.size());
  const gf::ContactTable table = seed000_table(l);
  const double reach = 2.0 * l.radius + kSkin;
  gf::Grains one = gf::test::lattice_grains(l, rcb, -1);
  gf::PeriodicImages im;
  im.box = box;
  gf::make_images(one, im, reach);
  REQUIRE(im.size() > 0);
  pair_forces(one, table);
  gf::fold_image_forces(one, im);

  gf::Grains g = gf::test::lattice_grains(l, rcb, mpi.rank());
  gf::DomainGhosts gh;
  gf::make_domain_ghosts(g, rcb, reach, mpi, gh, gf::GhostShell::half, &box);
  std::int64_t shifted = 0, own_images = 0;
  for (std::size_t r = 0; r < gh.shift.size(); ++r)
    for (const auto& s : gh.shift[r]) {
      const bool across = s[0] != 0.0 || s[1] != 0.0 || s[2] != 0.0;
      shifted += across;
      own_images += across && static_cast<int>(r) == mpi.rank();
    }
  CHECK(mpi.sum(shifted) > 0);
  CHECK(mpi.sum(own_images) > 0);
  // The ghosts stand at their owners' positions plus the shift: within the reach of this rank's box.
  for (std::size_t r = g.n_owned; r < g.n; ++r)
    CHECK(rcb.box(mpi.rank()).distance({g.pos.x[r], g.pos.y[r], g.pos.z[r]}) <= reach);
  pair_forces(g, table);
  gf::fold_domain_ghost_forces(g, gh, mpi);
  CHECK(compare_with_one(one, g, rcb, gh, reach, mpi, "periodic block") <= 1e-12);
}
