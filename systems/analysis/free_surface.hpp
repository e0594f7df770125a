// The free surface of a drum's bed in its cross-section: its tilt and level, its curvature (concave
// or convex) and how fast the grains at the surface run down it. Seed 000 reports that once petals
// form the flow pulses: the surface alternates concave and convex and its speed fast and slow; these
// are the quantities whose time series show that.
//
// Method. In the section plane (DrumSection: lab frame, up against gravity) the bed is cut into
// vertical columns two large diameters wide (narrower if that leaves fewer than ten across the
// drum), and each column's top is its third-highest grain top (v + r; so one or two grains in flight
// do not lift it). Over the middle 60 % of the bed's width (the ends curve up the wall) a
// least-squares line gives the angle and level, and a least-squares parabola v = a + b u + c u^2 the
// bulge: the parabola's height above its chord at the middle of that span, -c (L/2)^2 with L the
// span, positive for a convex (domed) surface and negative for a concave (dished) one. The surface
// speed is the mean velocity down the fitted line, weighted by volume, of the grains within the span
// whose tops lie within `depth_diameters` large diameters of the line (both sides: a grain hopping
// just above the surface is part of the flowing layer).
// Cost: two passes over the rows; no state between calls.
#pragma once

#include <cstddef>
#include <limits>
#include <span>

#include "systems/analysis/drum_section.hpp"

namespace gf {

struct SurfaceGrains {
  std::span<const double> x, y, z, r;  // m
  std::span<const double> vx, vy, vz;  // m/s; empty: no surface speed
};

struct FreeSurfaceSettings {
  double depth_diameters = 2.0;  // the surface layer's half-thickness, in diameters of the largest grain
};

struct FreeSurface {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  double angle = kNaN;  // rad, to the horizontal, positive rising towards `right`
  double level = kNaN;  // m, v of the fitted line at u = 0 (on the drum axis)
  double bulge = kNaN;  // m, the parabola over its chord at the span's middle: > 0 convex, < 0 concave
  double span = kNaN;   // m, width of the fitted part of the surface (L)
  double speed = kNaN;  // m/s, volume-weighted mean velocity of the surface layer down the line
  std::size_t layer_grains = 0;  // grains in that layer
};

// NaN fields where the bed has no surface to fit (fewer than three columns; the parabola needs
// three distinct columns too); speed NaN without velocities or without grains in the layer.
// std::invalid_argument if the columns differ in length or the settings are out of range.
FreeSurface free_surface(const SurfaceGrains& grains, const DrumSection& drum, const FreeSurfaceSettings& settings = {});

}  // namespace gf
