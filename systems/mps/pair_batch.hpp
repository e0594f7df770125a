// A row's neighbour pairs kLanes at a time, for the liquid's passes over the neighbour list: r_j - r_i through
// each pair's periodic image, and any column of the neighbours, read with hardware gathers. The arithmetic is the
// scalar NeighborPairs::rel's, lane by lane: (x_j - x_i) + image x period on the periodic axis (adding 0 where
// the image is 0 or the axis another).
#pragma once

#include <cstddef>
#include <cstdint>

#include "engine/simd.hpp"
#include "systems/mps/fluid_nodes.hpp"
#include "systems/mps/neighbors.hpp"

namespace gf {

struct PairBatches {
  const double *x, *y, *z;
  const std::int32_t* j;      // the pairs' neighbours (rows < 2^31)
  const std::int8_t* image;
  BatchD px, py, pz;          // the period on the periodic axis, 0 on the others

  PairBatches(const FluidNodes& f, const NeighborPairs& nb)
      : x(f.x.data()), y(f.y.data()), z(f.z.data()), j(reinterpret_cast<const std::int32_t*>(nb.j.data())),
        image(nb.image.data()), px(nb.periodic.axis == 0 ? nb.periodic.period() : 0.0),
        py(nb.periodic.axis == 1 ? nb.periodic.period() : 0.0), pz(nb.periodic.axis == 2 ? nb.periodic.period() : 0.0) {}

  // r_j - r_i for pairs k .. k + kLanes - 1 of row i.
  void rel(std::size_t i, std::size_t k, BatchD& dx, BatchD& dy, BatchD& dz) const {
    alignas(64) double im[kLanes];
    for (std::size_t l = 0; l < kLanes; ++l) im[l] = image[k + l];
    const BatchD s = BatchD::load_aligned(im);
    dx = (gather32(x, j + k) - BatchD(x[i])) + s * px;
    dy = (gather32(y, j + k) - BatchD(y[i])) + s * py;
    dz = (gather32(z, j + k) - BatchD(z[i])) + s * pz;
  }

  // col[j] for pairs k .. k + kLanes - 1.
  BatchD neighbours(const double* col, std::size_t k) const { return gather32(col, j + k); }
};

}  // namespace gf
