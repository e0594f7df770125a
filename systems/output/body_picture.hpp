// Side views of composite grains (seed 002's hopper snapshots): an orthographic projection onto a
// vertical plane, each member drawn as the filled silhouette of its dilated core (the convex hull of
// its core's projected vertices, grown by the dilation radius r: exactly the projection of the
// dilated convex member), members further from the viewer first and shaded darker, so the nearest
// shows where they overlap. Moving bodies take their colour (a group or a layer), fixed bodies grey;
// removed bodies are not drawn. The PNG is written by write_png (drum_picture.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "systems/bodies/bodies.hpp"
#include "systems/output/drum_picture.hpp"

namespace gf {

// The window drawn: the world box [lo, hi] (m) seen along axis `view` (2: along -z with x to the
// right; 0: along +x with z to the right), the axis `up` upwards in the image (1: y).
// Checkpoints store it as raw bytes: its padding is spelled out, so that no byte is left uninitialised.
struct BodyView {
  int view = 2;
  int right = 0;
  int up = 1;
  int padding_ = 0;
  std::array<double, 3> lo{}, hi{};
  int size = 800;  // px, the longer side of the image
  int padding_end_ = 0;
};
static_assert(sizeof(BodyView) == 72, "BodyView has no implicit padding (checkpoints hold its bytes)");

// The view of axis `view_axis` (2 or 0) with y up, over a box holding every body that is not removed
// plus a margin of a twentieth of its larger side (and down to `lowest` along y, when finite, so
// bodies falling from a hopper stay in the picture).
BodyView body_view(const Bodies& bodies, const Members& members, int view_axis, int size, double lowest);

// Colours: the Okabe-Ito palette for groups (blue, vermillion, bluish green, orange, reddish purple,
// sky blue, yellow, cycling), layers alternately blue and vermillion (the seed's hopper: 3 blue and 2
// red layers of five), fixed bodies grey.
Rgb group_colour(int group);
inline constexpr Rgb kFixedGrey{150, 150, 150};
Rgb layer_colour(int layer);

// Renders the bodies; colour[i] is body row i's colour (ignored for fixed bodies). Throws
// std::invalid_argument for a view of zero extent, a size outside [16, 8192] or too few colours.
Image render_body_picture(const Bodies& bodies, const Members& members, const std::vector<Rgb>& colour,
                          const BodyView& view);

// "pictures/time_0001.2500.png": the picture file name for a time (s), four decimals.
std::string body_picture_name(double t);

}  // namespace gf
