// Moon or petals: the segregation pattern of a binary mixture in a thin rotating drum (seed 000,
// Zhao & Cheng 2007, Figs. 3-5), read from grain positions in the drum's cross-section.
//
// Method. In the section plane (DrumSection: lab frame, up against gravity) take the rim band: the
// outermost shell of the bed, from the radius r_in about the drum axis out to the wall, with r_in
// chosen so the band holds a solid volume of `band_share` times the large species' total volume.
// In a moon (large grains outside a small core) the band is all large grains; in a petal pattern
// the small-grain lobes that radiate from the core reach the rim and cross the band, separated by
// large-grain wedges; in a mixture the band holds the mean composition everywhere. Along the band
// the large-grain volume fraction f(theta) is binned by the angle about the drum axis, over the
// bed's arc (the longest run of filled bins; its ends, where the free surface cuts the band, are
// trimmed), smoothed with a Gaussian in angle (ratio of smoothed volumes) and normalised:
// s = (f - p) / sqrt(p (1 - p)), p the large volume fraction of the whole bed (at p = 1/2, s = +1
// all large, -1 all small). Lobes are runs of s below m - w, left only when s rises above m + w
// (hysteresis, so noise about one level cannot make a run), m the mean of s over the arc and w the
// largest of h, 0.2 of the range of s and 2.5 sigma, sigma the spread of s expected in a random
// mixture from the number of large grains per smoothing window (few large grains: more noise).
// Decision:
//   fewer than min_large_in_band large grains in the band -> undecided (too few to tell)
//   2 or more lobes, contrast = mean |s| over the arc >= max(min_contrast, 2 sigma) -> petals,
//                                                          count = lobes
//   no lobe, or one lobe covering at most a third of the arc (the core bulges to the rim once:
//   "slight undulation"), and a large-rich band: mean s > h and > 3 standard errors of the mean
//   over the arc's independent smoothing windows      -> moon
//   anything else (a mixed bed, weak or irregular structure) -> undecided
// Lobes by radius. The same lobe count is made along rings about the drum axis at kRingRadii of the
// drum radius (each 2 kRingHalfWidth of it wide): how many small-grain lobes cross each radius. A
// lobe that stops short of the rim band counts at the radii it reaches, so the counts at 0.6 to 0.9 R
// tell a core with spikes from petals reaching the wall. A ring holds about ten large grains per
// smoothing window, too few for the band's Gaussian noise guard (a random mixture shows a false lobe
// in half the rings), so each run of a ring must also be poor in large grains beyond chance: the
// Poisson probability of at most its large-grain count, in its bins below the profile's mean, given
// the ring's mean count per volume, below ring_alpha per independent window of the arc
// (tests/pattern_test.cpp: the rate of false lobes on 60 random mixtures, and petals of 3, 5 and 7
// lobes counted at every ring). A ring wholly in the core or in the large shell, or mixed, reads 0 (its
// composition does not alternate); -1 where the ring holds too few large grains or less than 8
// bins of bed.
// The free-surface angle and level are free_surface()'s (free_surface.hpp).
// Cost: three passes over the rows and an atan2 per band grain; no state between calls.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "systems/analysis/drum_section.hpp"

namespace gf {

inline constexpr std::array<double, 4> kRingRadii{0.6, 0.7, 0.8, 0.9};  // of the drum radius
inline constexpr double kRingHalfWidth = 0.05;                           // of the drum radius

enum class PatternKind : int { Undecided = -1, Moon = 0, Petals = 1 };

struct PatternSettings {
  std::int32_t large_type = 1;         // species index of the large grains; every other species counts as small
  double band_share = 0.6;             // band volume / large-species volume (0.6: inside a moon's large shell)
  int bins = 180;                      // angular bins over the full circle (2 degrees)
  double smooth_bins = 1.5;            // Gaussian sigma of the smoothing, in bins (3 degrees)
  double trim_bins = 5;                // bins dropped at each end of the bed's arc (10 degrees: the surface cuts there)
  double hysteresis = 0.25;            // h, in units of sqrt(p (1 - p)); seed 000's bed: sigma ~0.1
  std::size_t min_large_in_band = 20;  // fewer large grains in the band: too few to tell, undecided
  double ring_alpha = 0.05;            // a ring's lobe test: nominal chance of a false lobe per ring (see above)
  double ring_trim_bins = 2;           // bins dropped at each end of a ring's arc (it meets the surface nearly square)
  double min_contrast = 0.2;           // below it the band shows no structure: undecided (mixed beds: < 0.1)
};

struct Pattern {
  PatternKind kind = PatternKind::Undecided;
  int petals = 0;             // small-grain lobes crossing the rim band; 0 unless kind is Petals
  double contrast = 0;        // mean |s| over the band's arc: 0 mixed, 1 fully segregated
  double surface_angle = 0;   // rad, free surface to the horizontal, positive rising towards `right`
                              // (to the right in the pictures); NaN if the bed has no surface to fit
  double surface_level = 0;   // m, v of the fitted surface line at u = 0 (on the drum axis); NaN with the angle
  double band_inner = 0;      // m, r_in
  double arc = 0;             // rad, the bed's arc in the band after trimming
  double noise = 0;           // sigma: spread of s a random mixture of this bed would show
  double large_fraction = 0;  // p
  std::array<int, kRingRadii.size()> ring_lobes{-1, -1, -1, -1};  // lobes crossing each ring; -1 undefined
};

struct PatternGrains {
  std::span<const double> x, y, z, r;  // m
  std::span<const std::int32_t> type;
};

// std::invalid_argument if the columns differ in length or the settings are out of range.
Pattern classify_pattern(const PatternGrains& grains, const DrumSection& drum, const PatternSettings& settings = {});

}  // namespace gf
