// Periodic boundaries for grains: a box whose faces along chosen axes are periodic, and the image
// rows that carry grains across them.
//
// At each neighbour rebuild the owned rows are wrapped into the box, and rows within reach of a
// periodic face get image rows (ghost rows after the owned ones) at their position shifted by one
// box length. Only shifts whose first nonzero component is positive are made (along x, y then z):
// a pair across a face, or across an edge or corner of several periodic faces, then appears exactly
// once in the half neighbour list, as (owned row, image of the other grain), the image on the side
// of the positive shift. Between rebuilds the positions are not wrapped again (they stay continuous,
// so every listed pair keeps its shift), and the images follow their owners: `refresh_images` copies
// position + shift, velocity and spin before the contacts are evaluated, and `fold_image_forces`
// adds the forces and torques the contacts left on images into their owners' rows. A box shorter than
// twice the reach of a pair would hold one grain pair twice; the scene loader refuses it.
//
// Systems: PeriodicRefresh (after the broadphase, before the contacts) writes the image rows'
// Position, Velocity, AngularVelocity; PeriodicFold (after the contacts) adds image rows' Force and
// Torque into their owners.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "engine/grains.hpp"
#include "engine/system.hpp"
#include "systems/periodic/periodic_box.hpp"

namespace gf {

struct PeriodicImages {
  PeriodicBox box;
  // Per image row n_owned + k: the owned row it copies and its shift (m).
  std::vector<std::uint32_t> owner;
  std::vector<double> sx, sy, sz;
  std::size_t size() const { return owner.size(); }
};

// Moves every owned row into [lo, hi) along the periodic axes (by whole box lengths).
void wrap_positions(Grains& g, const PeriodicBox& box);

// Replaces the table's ghost rows by the images of the owned rows within `reach` (m) of the box
// across a periodic face (positions, velocities, spins, radius, mass, species and id copied).
void make_images(Grains& g, PeriodicImages& im, double reach);

// Position + shift, velocity and spin of every image from its owner.
void refresh_images(Grains& g, const PeriodicImages& im);

// Adds each image row's Force and Torque into its owner's, in image order (the pair kernel starts the
// image rows from zero at each evaluation).
void fold_image_forces(Grains& g, const PeriodicImages& im);

// The owned row a row stands for: itself, or an image's owner.
inline std::uint32_t base_row(const Grains& g, const PeriodicImages& im, std::size_t row) {
  return row < g.n_owned ? static_cast<std::uint32_t>(row) : im.owner[row - g.n_owned];
}

class PeriodicRefresh : public SystemBase<PeriodicRefresh> {
 public:
  using Reads = gf::Reads<PeriodicImages>;
  using Writes = gf::Writes<Position, Velocity, AngularVelocity>;
  std::string_view name() const override { return "periodic_refresh"; }
  void run(World& world, const StepContext& step) override;
};

class PeriodicFold : public SystemBase<PeriodicFold> {
 public:
  using Reads = gf::Reads<PeriodicImages>;
  using Writes = gf::Writes<Force, Torque>;
  std::string_view name() const override { return "periodic_fold"; }
  void run(World& world, const StepContext& step) override;
};

}  // namespace gf
