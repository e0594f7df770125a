// Candidate pairs of a neighbour rebuild, searched by size class.
//
// In a mixture of 1 and 3 mm grains a small grain searching as far as a large partner could reach
// tests about three times more candidates than it can touch. The rows are split into a fine class
// (radius up to twice the smallest) and a coarse class (the rest). Every row searches its fine
// partners above it in the grid of all rows, whose cells are sized for the smallest pair, out to the
// reach of the fine class only, coarse rows masked out. The few coarse rows search the rest from
// their side: their fine partners below them in the same grid, and their coarse partners above them
// in a grid of the coarse rows alone, with cells sized for the largest pair. Each pair is found once
// and listed with its lower row. (LAMMPS' "neighbor multi" splits the search by type in the same
// spirit.) Without coarse rows (grains within a factor two in size) only the first search runs.
// Image rows of periodic boundaries (rows past n_owned, outside the grid) search the owned rows from
// their side, as the coarse rows do, and their pairs are listed with the owned row.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/column.hpp"
#include "engine/grains.hpp"
#include "systems/broadphase/cell_grid.hpp"

namespace gf {

class PairSearch {
 public:
  // Sets the classes and runs the coarse rows' search. `grid` is the grid of all rows (cells of at
  // least 2 r_min + skin), the rows sorted in its cell order. Returns false, having stopped, when the
  // coarse rows' pairs pass `most_pairs`.
  bool prepare(const Grains& g, const CellGrid& grid, double skin, std::size_t most_pairs);
  // Appends the rows j > i within r_i + r_j + skin of row i: fine partners, then coarse ones.
  void partners(const Grains& g, const CellGrid& grid, std::size_t i, std::vector<std::uint32_t>& out) const;

  bool split() const { return !coarse_row_.empty(); }
  double fine_radius() const { return r_fine_; }  // largest radius of the fine class
  std::size_t coarse_rows() const { return coarse_row_.size(); }

 private:
  // The coarse row c's pairs as (lower row, higher row): fine rows below it, coarse rows above it.
  void coarse_pairs(const Grains& g, const CellGrid& grid, std::size_t c, std::vector<std::uint64_t>& out) const;
  // Image row c's pairs (periodic boundaries) as (owned row, c): every owned row within reach.
  void image_pairs(const Grains& g, const CellGrid& grid, std::size_t c, std::vector<std::uint64_t>& out) const;
  void build_coarse_grid(const Grains& g, double rmax);

  double skin_ = 0.0;
  double r_fine_ = 0.0;  // largest fine radius (every radius when there is no split)
  double r_max_ = 0.0;   // largest radius of all
  std::vector<std::uint32_t> coarse_row_;  // coarse rows, increasing
  CellGrid coarse_;                        // their grid (points given in coarse_row_ order)
  // The coarse rows in coarse_'s cell order: positions on coarse_'s axes, radius, row.
  ColumnD cx_, cy_, cz_, cr_;
  std::vector<std::uint32_t> crow_;
  // The coarse rows' pairs by lower row: row i's partners are extra_[extra_start_[i] .. [i + 1]).
  std::vector<std::uint32_t> extra_start_, extra_;
  std::vector<std::vector<std::uint64_t>> chunk_pairs_;  // scratch per chunk of coarse rows
};

}  // namespace gf
