// The MPS kernel and particle-interaction models of seed 003 (Pan, Xie & Wan 2021, after Koshizuka & Oka 1996):
//   kernel (Zhang et al.)  W(r) = r_e / (0.85 r + 0.15 r_e) - 1  for r < r_e, else 0
//   number density         n_i = sum_{j != i} W(r_ij)
//   gradient               <grad phi>_i = d/n0 sum (phi_j + phi_i) / r_ij^2 (r_j - r_i) W_ij
//   divergence             <div u>_i    = d/n0 sum (r_j - r_i).(u_j - u_i) / r_ij^2 W_ij
//   Laplacian              <lap phi>_i  = 2d/(n0 lambda) sum (phi_j - phi_i) W_ij,  lambda = sum W r^2 / sum W
// with d the space dimension and n0, lambda taken from the initial lattice (square in 2D, cubic in 3D).
#pragma once

#include <cmath>

namespace gf {

inline double zhang_weight(double r, double re) { return r < re ? re / (0.85 * r + 0.15 * re) - 1.0 : 0.0; }

struct MpsConstants {
  int dim = 2;
  double l0 = 0;      // m, initial particle spacing
  double re = 0;      // m, kernel radius
  double n0 = 0;      // number density of the full lattice
  double lambda = 0;  // m^2, Laplacian model's lambda on the full lattice

  double grad_coef() const { return dim / n0; }                   // d/n0
  double lap_coef() const { return 2.0 * dim / (n0 * lambda); }  // 2d/(n0 lambda), 1/m^2
};

// n0 and lambda summed over every node of an infinite square (dim 2) or cubic (dim 3) lattice of spacing l0
// around a node, the node itself excluded.
MpsConstants lattice_constants(int dim, double l0, double re);

}  // namespace gf
