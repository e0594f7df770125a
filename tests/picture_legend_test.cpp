// The pictures' legends (systems/output/picture_legend.hpp), drawn with cairo: the picture's pixels
// inside the drum are left as they were, the band below holds text (dark pixels), each species' swatch
// in its exact colour or the colour bar's two ends, a scale bar of a round length, and the turning arrow
// sits in the top-right corner outside the drum.
#include "systems/output/picture_legend.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

using gf::Image;
using gf::PictureLegend;
using gf::Rgb;

namespace {

// A grey picture with a drum circle of 96 % of its width (as render_drum_picture draws it).
Image grey_picture(int size) {
  Image img;
  img.width = img.height = size;
  img.rgb.assign(3 * static_cast<std::size_t>(size) * size, 200);
  return img;
}

bool inside_drum(int x, int y, int size) {
  const double dx = x + 0.5 - 0.5 * size, dy = y + 0.5 - 0.5 * size;
  return std::sqrt(dx * dx + dy * dy) < 0.48 * size;
}

int count_in_band(const Image& img, int from_row, const std::function<bool(const Rgb&)>& pred) {
  int n = 0;
  for (int y = from_row; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) n += pred(img.at(x, y));
  return n;
}

}  // namespace

TEST_CASE("a legend band holds the time, the species swatches and a scale bar, and leaves the drum untouched") {
  const int size = 400;
  PictureLegend l;
  l.time = 2.5;
  l.angle = 3.75;
  l.omega = 1.5;
  l.turning = 1;
  l.entries = {{"small, 2 mm", Rgb{0, 114, 178}}, {"large, 6 mm", Rgb{230, 159, 0}}};
  l.px_per_m = 0.96 * size / 0.08;
  const Image pic = grey_picture(size);
  const Image out = gf::annotate_picture(pic, l);
  REQUIRE(out.width == size);
  REQUIRE(out.height == size + gf::legend_band_height(size));
  for (int y = 0; y < size; y += 3)
    for (int x = 0; x < size; x += 3)
      if (inside_drum(x, y, size)) REQUIRE(out.at(x, y) == pic.at(x, y));
  // Text: dark antialiased glyphs (a few hundred pixels at this size).
  CHECK(count_in_band(out, size, [](const Rgb& c) { return c[0] < 80 && c[1] < 80 && c[2] < 80; }) > 200);
  for (const auto& e : l.entries)
    CHECK(count_in_band(out, size, [&](const Rgb& c) { return c == e.colour; }) > 20);
  // The arrow: dark pixels in the top-right corner, none in the top-left.
  int arrow = 0, other = 0;
  for (int y = 0; y < size / 7; ++y)
    for (int x = 0; x < size / 7; ++x) {
      arrow += out.at(size - 1 - x, y)[0] < 100;
      other += out.at(x, y)[0] < 100;
    }
  CHECK(arrow > 20);
  CHECK(other == 0);
}

TEST_CASE("a speed legend is a colour bar from viridis' dark end to its yellow end") {
  PictureLegend l;
  l.time = 1.0;
  l.bar_max = 0.5;
  l.bar_unit = "m/s";
  const Image out = gf::annotate_picture(grey_picture(300), l);
  const Rgb low = gf::speed_colour(0.0, 0.5), high = gf::speed_colour(0.5, 0.5);
  CHECK(count_in_band(out, 300, [&](const Rgb& c) { return c == low; }) > 5);
  CHECK(count_in_band(out, 300, [&](const Rgb& c) { return c == high; }) > 5);
}

TEST_CASE("scale bars take round lengths") {
  CHECK(gf::round_length(0.0173) == Approx(0.01));
  CHECK(gf::round_length(0.0273) == Approx(0.02));
  CHECK(gf::round_length(0.06) == Approx(0.05));
  CHECK(gf::length_label(0.01) == "10 mm");
  CHECK(gf::length_label(0.002) == "2 mm");
  CHECK(gf::length_label(2.0) == "2 m");
}
