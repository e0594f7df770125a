#include "systems/decomposition/rcb.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace gf {

bool DomainBox::contains(const std::array<double, 3>& p) const {
  for (int d = 0; d < 3; ++d)
    if (p[d] < lo[d] || p[d] >= hi[d]) return false;
  return true;
}

double DomainBox::distance(const std::array<double, 3>& p) const {
  double s = 0.0;
  for (int d = 0; d < 3; ++d) {
    const double g = std::max({lo[d] - p[d], 0.0, p[d] - hi[d]});
    s += g * g;
  }
  return std::sqrt(s);
}

namespace {

int longest_axis(const DomainBox& b) {
  int a = 0;
  for (int d = 1; d < 3; ++d)
    if (b.hi[d] - b.lo[d] > b.hi[a] - b.lo[a]) a = d;
  return a;
}

}  // namespace

Rcb::Rcb(const DomainBox& domain, std::span<const double> x, std::span<const double> y, std::span<const double> z,
         std::span<const double> w, int ranks)
    : p_{x, y, z}, w_(w) {
  if (ranks < 1) throw std::invalid_argument("a decomposition needs at least one rank");
  if (y.size() != x.size() || z.size() != x.size() || (!w.empty() && w.size() != x.size()))
    throw std::invalid_argument("the points' coordinates and weights differ in length");
  boxes_.resize(static_cast<std::size_t>(ranks));
  std::vector<std::size_t> rows(x.size());
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = i;
  split(domain, rows, 0, rows.size(), ranks, 0);
  p_[0] = p_[1] = p_[2] = w_ = {};  // the points are not kept
}

int Rcb::split(const DomainBox& box, std::vector<std::size_t>& rows, std::size_t begin, std::size_t end, int ranks,
               int first_rank) {
  const int id = static_cast<int>(nodes_.size());
  nodes_.push_back({});
  if (ranks == 1) {
    nodes_[id].rank = first_rank;
    boxes_[static_cast<std::size_t>(first_rank)] = box;
    return id;
  }
  const int axis = longest_axis(box);
  const std::span<const double> c = p_[axis];
  std::sort(rows.begin() + begin, rows.begin() + end, [&](std::size_t a, std::size_t b) {
    return c[a] < c[b] || (c[a] == c[b] && a < b);
  });
  const int lower_ranks = ranks / 2;
  auto weight = [&](std::size_t i) { return w_.empty() ? 1.0 : w_[i]; };
  double total = 0.0;
  for (std::size_t k = begin; k < end; ++k) total += weight(rows[k]);
  const double target = total * lower_ranks / ranks;
  // The prefix of rows [begin, k) whose weight is nearest the target.
  std::size_t k = begin;
  double below = 0.0;
  while (k < end && std::abs(below + weight(rows[k]) - target) < std::abs(below - target)) below += weight(rows[k++]);
  double cut = box.lo[axis] + 0.5 * (box.hi[axis] - box.lo[axis]);
  if (k > begin && k < end) cut = 0.5 * (c[rows[k - 1]] + c[rows[k]]);
  else if (k == begin && k < end) cut = std::clamp(c[rows[k]], box.lo[axis], box.hi[axis]);
  else if (k == end && k > begin) cut = box.hi[axis];
  DomainBox lo_box = box, hi_box = box;
  lo_box.hi[axis] = hi_box.lo[axis] = cut;
  nodes_[id].axis = axis;
  nodes_[id].cut = cut;
  const int lower = split(lo_box, rows, begin, k, lower_ranks, first_rank);
  const int upper = split(hi_box, rows, k, end, ranks - lower_ranks, first_rank + lower_ranks);
  nodes_[id].lower = lower;
  nodes_[id].upper = upper;
  return id;
}

Rcb::Rcb(std::vector<RcbNode> nodes, std::vector<DomainBox> boxes) : nodes_(std::move(nodes)), boxes_(std::move(boxes)) {
  // Every node reached once from the root, children after their parent, each rank a leaf once.
  const auto n = static_cast<int>(nodes_.size());
  std::vector<int> seen_rank(boxes_.size(), 0), reached(nodes_.size(), 0);
  bool ok = n > 0 && !boxes_.empty();
  std::vector<int> pending{0};
  while (ok && !pending.empty()) {
    const int k = pending.back();
    pending.pop_back();
    ok = k >= 0 && k < n && reached[static_cast<std::size_t>(k)]++ == 0;
    if (!ok) break;
    const RcbNode& node = nodes_[static_cast<std::size_t>(k)];
    if (node.axis < 0) {
      ok = node.rank >= 0 && static_cast<std::size_t>(node.rank) < boxes_.size() &&
           seen_rank[static_cast<std::size_t>(node.rank)]++ == 0;
    } else {
      ok = node.axis < 3 && node.lower > k && node.upper > k;
      pending.push_back(node.lower);
      pending.push_back(node.upper);
    }
  }
  for (const int r : seen_rank) ok = ok && r == 1;
  if (!ok) throw std::invalid_argument("the cut tree is not one of these boxes' ranks");
}

double DomainBox::gap(const DomainBox& other) const {
  double d2 = 0.0;
  for (std::size_t d = 0; d < 3; ++d) {
    const double gap = std::max({0.0, other.lo[d] - hi[d], lo[d] - other.hi[d]});
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

DomainBox shifted(const DomainBox& b, const PeriodicBox& periodic, const std::array<int, 3>& s) {
  const std::array<double, 3> by = shift_metres(periodic, s);
  DomainBox out = b;
  for (std::size_t d = 0; d < 3; ++d) {
    out.lo[d] += by[d];
    out.hi[d] += by[d];
  }
  return out;
}

std::vector<int> box_peers(const Rcb& rcb, int rank, double within, const PeriodicBox* periodic) {
  const PeriodicBox box = periodic ? *periodic : PeriodicBox{};
  const std::vector<std::array<int, 3>> shifts = periodic_shifts(box, false);  // {0, 0, 0} without faces
  std::vector<int> out;
  for (int r = 0; r < rcb.ranks(); ++r) {
    if (r == rank) continue;
    bool near = false;
    for (const auto& s : shifts) near = near || rcb.box(rank).gap(shifted(rcb.box(r), box, s)) <= within;
    if (near) out.push_back(r);
  }
  return out;
}

int Rcb::owner_of(const std::array<double, 3>& p) const {
  int n = 0;
  while (nodes_[n].axis >= 0) n = p[nodes_[n].axis] < nodes_[n].cut ? nodes_[n].lower : nodes_[n].upper;
  return nodes_[n].rank;
}

}  // namespace gf
