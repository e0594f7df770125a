// Random sequential addition (RSA) of non-overlapping spheres into a region: the "random
// non-overlapping placement" that a pour starts from, before gravity settles it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "systems/fill/region.hpp"

namespace gf {

struct FillSpecies {
  std::int32_t type;
  double radius;  // m: every grain's, or the largest of `radii`
  std::size_t count;
  std::vector<double> radii = {};  // m: one per grain when they differ (a size distribution), else empty
};

struct PlacedGrain {
  std::array<double, 3> x;  // m
  std::int32_t type;
  double radius;  // m
  std::array<double, 3> v{}, w{};  // m/s, rad/s: at rest unless a state file gives them
  std::int64_t id = -1;             // a state file's id, kept; -1: the run gives one
  int line = 0;                     // the state file's line; 0: placed at random
};

// The request cannot be met (or is malformed); the message says what was reached and what to change.
class FillError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Places every species' count of spheres wholly inside `region`, overlapping neither each other
// nor `existing` (grains already in the world; touching is allowed). Largest radius first, because
// small grains fit between big ones but not the other way round, which is what makes dense
// bidisperse fills reachable; species of equal radius are interleaved at random so none of them
// is favoured by going first. The result is in placement order and depends only on the arguments
// (std::mt19937_64 with a portable mapping to doubles), not on the standard library.
// Throws FillError when a grain finds no free spot in max_attempts_per_grain random tries.
std::vector<PlacedGrain> place_random(const Region& region, std::vector<FillSpecies> species,
                                      std::uint64_t seed,
                                      std::span<const PlacedGrain> existing = {},
                                      std::size_t max_attempts_per_grain = 2000);

// The number of spheres of `radius` whose volumes add up to `fraction` of the region's volume,
// rounded to the nearest whole number.
std::size_t count_for_volume_fraction(const Region& region, double fraction, double radius);

}  // namespace gf
