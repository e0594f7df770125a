// Where the grains are, seen by the liquid (seed 003's coupling, eqs. 16-21): each grain's volume
// and force are shared among the liquid nodes within a smoothing radius h of its centre, and the
// liquid's fields are read at the grain with the same shares.
//
// Shares. For grain p and node i at distance r < h, w_ip = W(r / h) / sum_j W(r_jp / h), the sum
// over every node j within h of the grain in the set given (the coupling passes every node, fluid, wall
// and dummy alike, as the seed's kernel sum runs over all particles, or with coupling.share_with =
// "fluid_nodes" the fluid nodes only, so a grain beside a wall shares with the liquid alone), with
// W the Wendland C2 shape (1 - q)^4 (1 + 4 q), smooth and positive for q < 1. The shares of one
// grain sum to 1, so
//   solid volume at node i      S_i = sum_p w_ip V_p           (sum_i S_i = sum_p V_p exactly)
//   liquid fraction at node i   eps_i = max(eps_min, 1 - S_i / V_i), V_i = l0^dim the node's volume
//                               (in a locally averaged liquid the volume of mixture it stands for, coupled_liquid.hpp)
//   at the grain                eps_p = sum_i w_ip eps_i,  u_p = sum_i w_ip u_i
//   reaction on the liquid      f_i = -(1 / V_i) sum_p w_ip F_p (a force per volume, N/m^3), so that
//                               sum_i f_i V_i = -sum_p F_p: momentum conserved to rounding.
// h is a scene key of the coupling (the seed's grains are 2.67 node spacings across, so h must reach
// past a grain's own diameter for the shares to be smooth); a grain with no node within h has no
// shares, which compute_shares reports by throwing, naming the grain.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "systems/contact/vec3.hpp"

namespace gf {

struct PointSet {
  std::span<const double> x, y, z;  // m
  std::size_t size() const { return x.size(); }
};

// Per grain, its nodes and their shares (compressed rows: grain p's are [start[p], start[p + 1])).
struct GrainShares {
  std::vector<std::uint32_t> start;
  std::vector<std::uint32_t> node;
  std::vector<double> share;
};

// Wendland C2 shape, unnormalised (the shares normalise it): (1 - q)^4 (1 + 4 q) for 0 <= q < 1.
double smoothing_shape(double q);

// std::invalid_argument for h not positive and finite; std::runtime_error for a grain with no node
// within h (its index and position in the message, and the fix: a larger smoothing radius).
GrainShares compute_shares(const PointSet& grains, const PointSet& nodes, double h);

// As compute_shares, on nodes that repeat along `axis` (0, 1 or 2) with period [lo, hi): a grain within h
// of one end shares with the nodes near the other end too, through their images one period away, so a bed
// that fills a periodic column has no seam in its liquid fraction. The shares name the nodes themselves.
GrainShares compute_shares_periodic(const PointSet& grains, const PointSet& nodes, double h, int axis, double lo,
                                    double hi);

// S_i: the grains' volumes (m^3) shared onto the nodes.
std::vector<double> solid_volume(const GrainShares& s, std::span<const double> grain_volume, std::size_t nodes);

// eps_i = max(eps_min, 1 - S_i / V_i).
std::vector<double> liquid_fraction(std::span<const double> solid, double node_volume, double eps_min);
// The same with each node's own volume V_i.
std::vector<double> liquid_fraction(std::span<const double> solid, std::span<const double> volume, double eps_min);

// sum_i w_ip phi_i per grain.
std::vector<double> at_grains(const GrainShares& s, std::span<const double> node_field);

// f_i = -(1 / V_i) sum_p w_ip F_p (N/m^3), per component.
void spread_reaction(const GrainShares& s, std::span<const V3<double>> grain_force, double node_volume,
                     std::span<V3<double>> node_force_density);

}  // namespace gf
