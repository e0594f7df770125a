// What a picture says about itself, drawn with cairo (antialiased shapes and text): a band below the
// picture holds the time, the rotation angle and the direction of turning, a scale bar, and either the
// species with their sizes or a colour bar with its range and unit; an arrow in the picture's top-right
// corner (outside the drum) shows which way the drum turns.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "systems/output/drum_picture.hpp"

namespace gf {

struct PictureLegend {
  double time = std::numeric_limits<double>::quiet_NaN();   // s
  double angle = std::numeric_limits<double>::quiet_NaN();  // rad
  double omega = 0.0;  // rad/s, magnitude
  int turning = 0;     // +1 counter-clockwise as seen in the picture, -1 clockwise, 0 not turning
  struct Entry {
    std::string label;  // "small, 1 mm"
    Rgb colour;
  };
  std::vector<Entry> entries;  // a swatch each (colouring by species)
  double bar_max = 0.0;        // > 0: a viridis colour bar from 0 to bar_max (colouring by speed)
  std::string bar_unit;        // "m/s"
  double px_per_m = 0.0;       // > 0: a scale bar of a round length
};

// The picture with its legend band below it (the picture's pixels keep their place: rows 0 to
// height - 1 are the picture's, changed only by the arrow in the corner outside the drum).
// std::runtime_error if cairo cannot draw.
Image annotate_picture(const Image& picture, const PictureLegend& legend);

// The band's height for a picture `width` pixels wide.
int legend_band_height(int width);

// A round length (1, 2 or 5 times a power of ten, m) near `target` m, and its label ("10 mm").
double round_length(double target);
std::string length_label(double metres);

}  // namespace gf
