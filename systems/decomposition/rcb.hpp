// Recursive coordinate bisection: a box split among P ranks by weighted median cuts.
//
// The box is cut across its longest axis so that the rows on the lower side carry P_lo / P of the
// weight (P_lo = P / 2), and each side is split again among its ranks until every rank has one box.
// Ranks are numbered lower side first. Each cut lies midway between the last row kept below it and
// the next row; a row on a cut belongs to the upper side, so the boxes are half-open and tile the
// box without gaps or overlaps. The cut is the prefix of rows (sorted by coordinate, ties by row)
// whose weight is nearest the target, so each cut misses its target by at most half the heaviest
// row's weight, and a rank's weight misses W / P by less than one row's weight for P up to 8 (rows
// that share the coordinate of a cut all go to the upper side, so a cut through many equal
// coordinates may miss by their weight instead). The result depends on the points and weights
// alone: every rank computing it gets the same boxes.
//
// Why not Zoltan (libtrilinos-zoltan-dev): its RCB is the same algorithm behind a dependency of
// its own (Trilinos' build, its parameter strings, its MPI-parallel median search). The split here
// is about a hundred lines, deterministic by construction and testable without MPI. Weights are
// the rows' measured cost (default 1). At thousands of ranks, the points would be sampled or the
// medians searched in parallel; the boxes and owner_of keep their meaning.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include "systems/periodic/periodic_box.hpp"

namespace gf {

struct DomainBox {
  std::array<double, 3> lo{}, hi{};  // m; a point p is inside when lo <= p < hi on every axis
  bool contains(const std::array<double, 3>& p) const;
  // Distance (m) from p to the box, 0 inside.
  double distance(const std::array<double, 3>& p) const;
  // Distance (m) between the two boxes, 0 where they touch or overlap.
  double gap(const DomainBox& other) const;
  double volume() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

// One node of the cut tree: a cut (axis >= 0) with its two children, or a leaf holding a rank.
struct RcbNode {
  int axis = -1;      // -1: a leaf
  double cut = 0.0;   // m; below goes to `lower`, at or above to `upper`
  int lower = -1, upper = -1;  // children (node indices)
  int rank = 0;       // a leaf's rank
};

class Rcb {
 public:
  // Splits `domain` among `ranks` by the points (x, y, z) with weights w (empty: every weight 1).
  Rcb(const DomainBox& domain, std::span<const double> x, std::span<const double> y, std::span<const double> z,
      std::span<const double> w, int ranks);
  // The same split again from its tree and boxes (a checkpoint's); std::invalid_argument when they
  // are not a tree whose leaves name each of the boxes' ranks once.
  Rcb(std::vector<RcbNode> nodes, std::vector<DomainBox> boxes);
  const std::vector<RcbNode>& nodes() const { return nodes_; }

  int ranks() const { return static_cast<int>(boxes_.size()); }
  const DomainBox& box(int rank) const { return boxes_[static_cast<std::size_t>(rank)]; }
  const std::vector<DomainBox>& boxes() const { return boxes_; }
  // The rank whose box holds p; a point outside the domain goes to the nearest box along the cuts.
  int owner_of(const std::array<double, 3>& p) const;

 private:
  using Node = RcbNode;
  int split(const DomainBox& box, std::vector<std::size_t>& rows, std::size_t begin, std::size_t end, int ranks,
            int first_rank);

  std::span<const double> p_[3];
  std::span<const double> w_;
  std::vector<Node> nodes_;
  std::vector<DomainBox> boxes_;
};

// The ranks other than `rank` whose boxes lie within `within` (m) of its box, ascending: the ranks
// a rank exchanges with when nothing travels farther (a symmetric relation). With a periodic box,
// also those within `within` across its periodic faces (a box shifted by whole box lengths).
std::vector<int> box_peers(const Rcb& rcb, int rank, double within, const PeriodicBox* periodic = nullptr);

// The box shifted by s[d] box lengths of `periodic` along each axis d.
DomainBox shifted(const DomainBox& b, const PeriodicBox& periodic, const std::array<int, 3>& s);

}  // namespace gf
