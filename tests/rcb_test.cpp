// Recursive coordinate bisection: each rank's weight is within one row's weight of an equal share,
// the boxes tile the domain (volumes add up, and every point has exactly one box, the one owner_of
// names), the result is the same when computed again, for 1 to 8 ranks, and when rebuilt from its
// tree and boxes; a broken tree is refused.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "systems/decomposition/rcb.hpp"

namespace {

struct Points {
  std::vector<double> x, y, z, w;
};

// n points in a 0.3 x 0.1 x 0.2 box, clustered towards one corner, with weights in [0.5, 2] (or 1).
Points make_points(std::size_t n, bool weighted, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), w(0.5, 2.0);
  Points p;
  for (std::size_t i = 0; i < n; ++i) {
    p.x.push_back(0.3 * u(rng) * u(rng));
    p.y.push_back(0.1 * u(rng));
    p.z.push_back(0.2 * std::sqrt(u(rng)));
    p.w.push_back(weighted ? w(rng) : 1.0);
  }
  return p;
}

const gf::DomainBox kDomain{{0.0, 0.0, 0.0}, {0.3, 0.1, 0.2}};

gf::Rcb split(const Points& p, int ranks) { return gf::Rcb(kDomain, p.x, p.y, p.z, p.w, ranks); }

}  // namespace

TEST_CASE("RCB gives each rank an equal share of the weight within one row's weight", "[rcb]") {
  for (bool weighted : {false, true})
    for (int ranks = 1; ranks <= 8; ++ranks) {
      const Points p = make_points(5000, weighted, 7 + static_cast<unsigned>(ranks));
      const gf::Rcb rcb = split(p, ranks);
      std::vector<double> load(static_cast<std::size_t>(ranks), 0.0);
      double total = 0.0, heaviest = 0.0;
      for (std::size_t i = 0; i < p.x.size(); ++i) {
        load[static_cast<std::size_t>(rcb.owner_of({p.x[i], p.y[i], p.z[i]}))] += p.w[i];
        total += p.w[i];
        heaviest = std::max(heaviest, p.w[i]);
      }
      for (double l : load) {
        INFO("ranks " << ranks << (weighted ? ", weighted" : ", unit weights") << ": load " << l << " of " << total);
        CHECK(std::abs(l - total / ranks) <= heaviest);
      }
    }
}

TEST_CASE("RCB boxes tile the domain without gaps or overlaps", "[rcb]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int ranks = 1; ranks <= 8; ++ranks) {
    const gf::Rcb rcb = split(make_points(2000, true, 100 + static_cast<unsigned>(ranks)), ranks);
    double volume = 0.0;
    for (const gf::DomainBox& b : rcb.boxes()) {
      for (int d = 0; d < 3; ++d) CHECK(b.lo[d] <= b.hi[d]);
      volume += b.volume();
    }
    CHECK(volume == Approx(kDomain.volume()).epsilon(1e-12));
    // Every probe point inside the domain lies in exactly one box, the owner's.
    for (int k = 0; k < 20000; ++k) {
      const std::array<double, 3> q{0.3 * u(rng), 0.1 * u(rng), 0.2 * u(rng)};
      int inside = 0, which = -1;
      for (int r = 0; r < ranks; ++r)
        if (rcb.box(r).contains(q)) ++inside, which = r;
      REQUIRE(inside == 1);
      REQUIRE(which == rcb.owner_of(q));
    }
  }
}

TEST_CASE("RCB is deterministic and splits across the longest axis first", "[rcb]") {
  const Points p = make_points(3000, true, 42);
  for (int ranks : {2, 3, 5, 6, 7}) {
    const gf::Rcb a = split(p, ranks), b = split(p, ranks);
    for (int r = 0; r < ranks; ++r) {
      CHECK(a.box(r).lo == b.box(r).lo);
      CHECK(a.box(r).hi == b.box(r).hi);
    }
  }
  // Two ranks: one cut across x, the domain's longest axis.
  const gf::Rcb two = split(p, 2);
  CHECK(two.box(0).lo[0] == 0.0);
  CHECK(two.box(0).hi[0] == two.box(1).lo[0]);
  CHECK(two.box(1).hi[0] == 0.3);
  CHECK(two.box(0).hi[1] == 0.1);
  CHECK(two.box(0).hi[2] == 0.2);
}

TEST_CASE("RCB with more ranks than points leaves some boxes empty but still tiles", "[rcb]") {
  const std::vector<double> x{0.1}, y{0.05}, z{0.1};
  const gf::Rcb rcb(kDomain, x, y, z, {}, 3);
  double volume = 0.0;
  for (const gf::DomainBox& b : rcb.boxes()) volume += b.volume();
  CHECK(volume == Approx(kDomain.volume()).epsilon(1e-12));
  const int owner = rcb.owner_of({0.1, 0.05, 0.1});
  CHECK(rcb.box(owner).contains({0.1, 0.05, 0.1}));
}

TEST_CASE("RCB rebuilt from its tree and boxes (a checkpoint's) names the same owners", "[rcb]") {
  const Points p = make_points(2000, false, 5);
  for (int ranks = 1; ranks <= 8; ++ranks) {
    const gf::Rcb rcb = split(p, ranks);
    const gf::Rcb again(rcb.nodes(), rcb.boxes());
    REQUIRE(again.ranks() == ranks);
    for (std::size_t i = 0; i < p.x.size(); ++i)
      REQUIRE(again.owner_of({p.x[i], p.y[i], p.z[i]}) == rcb.owner_of({p.x[i], p.y[i], p.z[i]}));
  }
  // A tree that loops, names a rank twice or misses one is refused.
  const gf::Rcb rcb = split(p, 4);
  std::vector<gf::RcbNode> loop = rcb.nodes(), twice = rcb.nodes();
  loop[0].lower = 0;
  for (gf::RcbNode& n : twice)
    if (n.axis < 0 && n.rank == 3) n.rank = 2;
  CHECK_THROWS_AS(gf::Rcb(loop, rcb.boxes()), std::invalid_argument);
  CHECK_THROWS_AS(gf::Rcb(twice, rcb.boxes()), std::invalid_argument);
  CHECK_THROWS_AS(gf::Rcb(rcb.nodes(), {rcb.boxes().begin(), rcb.boxes().begin() + 3}), std::invalid_argument);
}

TEST_CASE("box peers: the ranks whose boxes lie within a distance, a symmetric relation", "[rcb]") {
  // Three boxes in a row along x (the long axis of a 0.6 m domain): cuts at 0.2 and 0.4 m, so 0
  // and 2 are 0.2 m apart and each touches 1.
  const std::vector<double> x{0.1, 0.3, 0.5}, y{0.05, 0.05, 0.05}, z{0.1, 0.1, 0.1};
  const gf::Rcb rcb(gf::DomainBox{{0.0, 0.0, 0.0}, {0.6, 0.1, 0.2}}, x, y, z, {}, 3);
  CHECK(gf::box_peers(rcb, 0, 0.05) == std::vector<int>{1});
  CHECK(gf::box_peers(rcb, 1, 0.05) == std::vector<int>{0, 2});
  CHECK(gf::box_peers(rcb, 2, 0.05) == std::vector<int>{1});
  CHECK(gf::box_peers(rcb, 0, 0.2) == std::vector<int>{1, 2});  // the gap itself counts as within
  const Points p = make_points(3000, false, 9);
  const gf::Rcb eight = split(p, 8);
  for (int a = 0; a < 8; ++a)
    for (const int b : gf::box_peers(eight, a, 0.02)) {
      const std::vector<int> back = gf::box_peers(eight, b, 0.02);
      CHECK(std::find(back.begin(), back.end(), a) != back.end());
    }
}
