// Mixing measures of a binary mixture: Lacey's index over cubic sample cells, and a radial and a
// depth segregation index for the cross-section of a rotating drum. Species A is one species (the scenes
// take the larger one); every other grain counts as B. Both read volume fractions: the grains of a
// binary mixture usually differ in size, and a fraction by number would weigh a large grain as
// much as a small one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>

#include "engine/grains.hpp"
#include "systems/analysis/drum_section.hpp"
#include "systems/analysis/sample_cells.hpp"
#include "systems/contact/vec3.hpp"

namespace gf {

// Lacey's mixing index M = (s0^2 - s^2) / (s0^2 - sr^2), 0 fully segregated, 1 random at the scale
// of the cells (a mixture more even than random, such as an ordered lattice, exceeds 1).
//   f_i   volume fraction of A in cell i (cubic, edge `cell`, sample_cells.hpp); a cell is counted
//         when it holds at least `min_grains` grains
//   p     volume fraction of A over every grain
//   s^2   sum V_i (f_i - p)^2 / sum V_i over the counted cells, V_i the cell's solid volume.
//         Weighted by solid volume, not the unweighted mean over cells that is common with grains
//         of one size: with two sizes a cell's volume changes with its share of large grains, and
//         the unweighted mean over-counts the cells that a few large grains fill. In a random
//         mixture of a 2:1 diameter ratio (exact binomial sums), E[s^2] / sr^2 is 1.05-1.07
//         weighted against 1.24-1.27 unweighted at 27 grains per cell, 1.01-1.02 against
//         1.05-1.06 at 125. A fully segregated bed gives s^2 = s0^2 exactly when every grain is in
//         a counted cell, whatever the cells hold. It is also the spread that Danckwerts' index
//         (metrics.hpp) reads: I^2 = s^2 / s0^2.
//   s0^2  p (1 - p): every cell holds one species only
//   sr^2  p (1 - p) [(1 - p) w_A + p w_B] / V, the variance of a random mixture in cells of solid
//         volume V, the mean solid volume of the counted cells (Poole, Taylor and Wall 1964), with
//         w_X = sum v^2 / sum v over the grains of species X (v a grain's volume: the
//         volume-weighted mean grain volume). For grains of one size it is p (1 - p) / n, n the
//         mean number of grains per counted cell, Lacey's form; for sizes that differ, p (1 - p) / n
//         is off by a factor of about 2.5 at a 2:1 diameter ratio (too small at equal volumes of
//         the two species, too large at equal numbers).
// M depends on the cell size (smaller cells: fewer grains, a larger sr^2), so the cell edge and the
// grains per counted cell are reported with it. NaN (the other fields as far as known) when p is 0
// or 1, no cell is counted, or the cells are so small that sr^2 >= s0^2.
struct LaceyIndex {
  double index = std::numeric_limits<double>::quiet_NaN();  // M
  double variance = 0.0;         // s^2
  double segregated = 0.0;       // s0^2
  double random = 0.0;           // sr^2
  double fraction_a = 0.0;       // p
  std::size_t cells = 0;         // cells counted
  double grains_per_cell = 0.0;  // mean number of grains per counted cell
  double cell = 0.0;             // m, the cells' edge
};

// `min_grains`: 10 by default. Below it a cell's fraction moves in steps of a tenth or more, and
// sr^2, a large-count form, is off by up to a quarter at a 2:1 diameter ratio. A full cell of the
// scenes' default edge, three large diameters, holds about 30 large grains at a solid fraction of
// 0.6 (many more small ones), so 10 leaves out only the cells that a wall or the free surface cuts
// to less than a third.
// std::invalid_argument for a cell that is not positive and finite or min_grains < 1.
LaceyIndex lacey_index(const Grains& g, std::int32_t type_a, double cell, int min_grains = 10);

// Radial segregation in the cross-section of a drum (DrumSection: section-plane coordinates u, v;
// the coordinate along the axis is ignored, so axial bands do not show in it).
//   centre     the bed's centroid in the section, (u_c, v_c) = sum v_i (u_i, v_i) / sum v_i
//   rho_i      distance of grain i from it in the section plane
//   core       the grains nearest the centre, taken in order of rho (ties by id), up to the one with
//              which their solid volume first reaches half of the bed's; periphery: the others
//   phi_core, phi_periphery   volume fraction of A in the core and in the periphery
//   index      (phi_periphery - phi_core) / (phi_periphery + phi_core), in [-1, 1]:
//              +1 when A is only in the periphery, -1 when only in the core, about 0 mixed.
// In a rotating drum the small grains gather in a core and the large at the periphery, so the
// index of the large species rises towards +1 as the bed segregates. Every owned grain counts,
// grains in flight included. NaN when the periphery is empty or the bed holds no A.
struct RadialSegregation {
  double index = std::numeric_limits<double>::quiet_NaN();
  double core_fraction = std::numeric_limits<double>::quiet_NaN();       // phi_core
  double periphery_fraction = std::numeric_limits<double>::quiet_NaN();  // phi_periphery
  double split_radius = 0.0;                                             // m, rho of the core's last grain
  double centre_u = 0.0, centre_v = 0.0;                                 // m, (u_c, v_c)
};
RadialSegregation radial_segregation(const Grains& g, std::int32_t type_a, const DrumSection& drum);

// Layering against the free surface, which the radial index can miss: a bed whose heavy grains lie
// under a light surface layer and along the wall has A both in the core and in the periphery about
// the centroid, and reads as mixed there (seed 001's equal-size, unequal-density beds).
//   depth_i    distance of grain i's centre below the free surface, perpendicular to it: the line
//              v = level + u tan(angle) in the section plane (the fit of pattern.hpp)
//   deep       the deepest grains, taken in order of depth (ties by id), up to the one with which
//              their solid volume first reaches half of the bed's; shallow: the others
//   index      (phi_deep - phi_shallow) / (phi_deep + phi_shallow), in [-1, 1]: +1 when A lies only
//              in the deep half, -1 only in the shallow half, about 0 mixed.
// A core of A (the radial index near -1) sits mid-depth and splits between the halves, so the two
// indices together tell a core from layers. NaN when the surface is not known (NaN angle or level)
// or the bed holds no A.
struct DepthSegregation {
  double index = std::numeric_limits<double>::quiet_NaN();
  double deep_fraction = std::numeric_limits<double>::quiet_NaN();     // phi_deep
  double shallow_fraction = std::numeric_limits<double>::quiet_NaN();  // phi_shallow
  double split_depth = 0.0;                                            // m, depth of the deep half's last grain
};
DepthSegregation depth_segregation(const Grains& g, std::int32_t type_a, const DrumSection& drum,
                                   double surface_angle, double surface_level);

// Mixture quality of a transverse layer of a continuous mixer (seed 004): the grains whose centres
// lie within thickness / 2 of the plane at `distance` (m) from `inlet` along the unit `axis` (the
// seed takes the largest grain diameter as the thickness), binned into square sample cells of edge
// `cell` in that plane, their corners on a grid through `inlet` (a grain belongs whole to the cell
// holding its centre). Over the cells with
// at least `min_grains` grains, with c_i the volume fraction of A in cell i and v_i its solid volume:
//   c       the layer's mean fraction of A, sum v_i c_i / V, V = sum v_i
//   Vc      the inhomogeneity coefficient, (1 / c) sqrt(sum v_i (c_i - c)^2 / V): 0 when every cell
//           holds the mean, sqrt((1 - c) / c) when every cell holds one species
//   lacey   Lacey's index of the same cells, (s0^2 - s^2) / (s0^2 - sr^2) as lacey_index() defines it
//           (s^2 = (Vc c)^2, s0^2 = c (1 - c), sr^2 from the layer's grain volumes)
// NaN (the counts as known) when no cell is counted or the layer holds no A.
// std::invalid_argument for an axis that is not a non-zero finite vector, a thickness or a cell
// that is not positive and finite, or min_grains < 1.
struct LayerMixing {
  double vc = std::numeric_limits<double>::quiet_NaN();
  double lacey = std::numeric_limits<double>::quiet_NaN();
  double fraction_a = std::numeric_limits<double>::quiet_NaN();  // c
  std::size_t cells = 0;                                         // cells counted
  std::int64_t grains = 0;                                       // grains in the counted cells
  double grains_per_cell = 0.0;
};
LayerMixing layer_mixing(const Grains& g, std::int32_t type_a, const V3<double>& inlet, const V3<double>& axis,
                         double distance, double thickness, double cell, int min_grains = 10);

// The same in two parts, so that the cells of several samples can be pooled: the layer's grains
// binned into its cells (keyed by integer cell coordinates), and the quality of binned cells. Pooling
// samples taken over a steady state (LayerCells::add) counts each cell's contents summed over time,
// as a measurement of the grains that pass through a cross-section does.
struct LayerCells {
  std::map<std::pair<std::int64_t, std::int64_t>, CellComposition> cells;
  double volume_a = 0.0, volume = 0.0, volume_sq_a = 0.0, volume_sq = 0.0;  // totals of the layer's grains
  void add(const LayerCells& more);
};
LayerCells layer_cells(const Grains& g, std::int32_t type_a, const V3<double>& inlet, const V3<double>& axis,
                       double distance, double thickness, double cell);
LayerMixing layer_quality(const LayerCells& cells, int min_grains);

}  // namespace gf
