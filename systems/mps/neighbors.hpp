// Neighbour pairs of the liquid: a cell grid built by counting sort each step, then a compressed row list (CSR)
// of every node j within the search radius of node i. The search radius is the kernel radius plus a skin, so the
// one list built at the start of a step still holds every pair within r_e after the particles moved during the
// step (the CFL limit keeps that motion well under the skin). Kernel weights are recomputed from current
// positions whenever positions change (number_density).
//
// The list is rebuilt only when a pair could come within r_e unlisted by the end of the coming step (Verlet). Two
// fluid nodes approach each other only by the difference of their displacements, so a fluid node's displacement
// since the build is taken from the fluid's common drift and may reach half the skin; a wall or dummy node never
// moves, so against those a fluid node's whole displacement may reach the skin. A liquid carried along a periodic
// pipe as a whole thus keeps its list for several steps, where a bound on the whole displacement against half
// the skin (with the coming step's margin 2 dt |u|) rebuilt it every step above 1.67 m/s (skin 5 mm, dt = 5e-4 s).
//
// One axis may be periodic: positions are wrapped into [lo, hi) before the list is built, and each pair keeps the
// image (-1, 0, +1 periods) through which it was found, so distances stay continuous through the step.
#pragma once

#include <cstdint>
#include <vector>

#include "systems/mps/fluid_nodes.hpp"

namespace gf {

struct Periodicity {
  int axis = -1;  // -1: none, 0: x, 1: y, 2: z
  double lo = 0, hi = 0;  // m
  double period() const { return hi - lo; }
};

struct NeighborPairs {
  std::vector<std::uint32_t> start;  // size rows + 1
  std::vector<std::uint32_t> j;
  std::vector<std::int8_t> image;    // periods added to j's coordinate along the periodic axis
  std::vector<double> w;             // kernel weight at current positions
  Periodicity periodic;
  double radius = 0;                 // m, search radius the list was built with
  std::vector<double> x0, y0, z0;    // m, positions at the last build
  std::int64_t builds = 0;

  std::size_t rows() const { return start.empty() ? 0 : start.size() - 1; }
  std::size_t pairs() const { return j.size(); }

  // r_j - r_i for pair k of row i, through the pair's periodic image.
  void rel(const FluidNodes& f, std::size_t i, std::size_t k, double& dx, double& dy, double& dz) const {
    const std::uint32_t q = j[k];
    dx = f.x[q] - f.x[i];
    dy = f.y[q] - f.y[i];
    dz = f.z[q] - f.z[i];
    if (image[k] != 0) {
      const double s = image[k] * periodic.period();
      (periodic.axis == 0 ? dx : periodic.axis == 1 ? dy : dz) += s;
    }
  }
};

// Moves every node back into [lo, hi) along the periodic axis (no-op without one).
void wrap_periodic(FluidNodes& f, const Periodicity& per);

// True when there was no build, or when some fluid node, with the motion of the coming step added (2 dt |u|,
// room for acceleration), would stand farther than skin/2 from where the fluid's common drift since the build
// has taken it, or farther than the skin from where it was at the build.
bool neighbors_stale(const FluidNodes& f, const NeighborPairs& nb, double skin, double dt);

// Rebuilds the list: pairs (i, j), i != j, closer than `radius`. Dummy rows keep only their wall neighbours, the
// only ones they read (pressure extrapolation). Deterministic: each row lists its neighbours in cell-scan order.
void build_neighbors(const FluidNodes& f, double radius, const Periodicity& per, NeighborPairs& out);

}  // namespace gf
