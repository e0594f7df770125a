// Contacts between grains of a size distribution. The contact table holds a law's constants per species
// pair, computed for one nominal grain of each species (its smallest, whose contacts also set the
// critical step). When a species' grains differ in size, a law whose constants depend on the bodies'
// masses and radii declares how they scale, and the drivers rescale them to each contact's own grains:
//   template <class T> static void resize(std::array<T, kConstants>& k, const SizeRatio<T>& q);
// q holds the contact's effective mass, inertia and radius over the nominal pair's, and each grain's
// radius over its nominal one. The rescaled constants equal those computed from the grains themselves
// (tests/size_scaling_test.cpp checks both laws against constants() to rounding). A table of fixed
// sizes is not rescaled at all, so those scenes run the arithmetic they always ran.
#pragma once

#include <array>
#include <concepts>

namespace gf {

template <class T>
struct SizeRatio {
  T m;        // m*/m*_nominal (a wall: the grain's own mass over the nominal grain's)
  T inertia;  // I*/I*_nominal, with I = 2/5 m r^2 for each sphere
  T r;        // R*/R*_nominal
  T ri, rj;   // each grain's radius over its nominal one (rj = 1 against a wall)
};

template <class L>
concept SizedLaw = requires(std::array<double, L::kConstants>& k, const SizeRatio<double>& q) {
  L::resize(k, q);
};

// A pair of grains (masses m, radii r) against the nominal pair (m0, r0). The factor 2/5 of the
// spheres' inertias cancels in the ratio.
template <class T>
SizeRatio<T> pair_size_ratio(const T& mi, const T& mj, const T& ri, const T& rj, const T& mi0, const T& mj0,
                             const T& ri0, const T& rj0) {
  const T ii = mi * ri * ri, ij = mj * rj * rj, ii0 = mi0 * ri0 * ri0, ij0 = mj0 * rj0 * rj0;
  return {(mi * mj / (mi + mj)) / (mi0 * mj0 / (mi0 + mj0)), (ii * ij / (ii + ij)) / (ii0 * ij0 / (ii0 + ij0)),
          (ri * rj / (ri + rj)) / (ri0 * rj0 / (ri0 + rj0)), ri / ri0, rj / rj0};
}

// A grain against a wall: its own mass, inertia and radius over the nominal grain's.
template <class T>
SizeRatio<T> wall_size_ratio(const T& mi, const T& ri, const T& mi0, const T& ri0) {
  const T q = ri / ri0, qm = mi / mi0;
  return {qm, qm * q * q, q, q, T(1.0)};
}

}  // namespace gf
