// PNG pictures of a drum's cross-section seen along its axis (seed 000, Figs. 2-7): grains as
// filled discs of their true radius, coloured by species or by speed, and the drum's inner circle.
// The view is the lab frame of DrumSection: gravity points down the image, the drum axis at the
// viewer. Grains further back are drawn first, so the nearest grain shows where discs overlap.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include "systems/analysis/drum_section.hpp"

namespace gf {

using Rgb = std::array<std::uint8_t, 3>;

// Paints colour c with coverage a in [0, 1] over the pixel whose three bytes start at p.
inline void blend(std::uint8_t* p, const Rgb& c, double a) {
  for (int k = 0; k < 3; ++k) p[k] = static_cast<std::uint8_t>(std::lround(a * c[k] + (1.0 - a) * p[k]));
}

// Species colours from the Okabe-Ito palette (distinguishable with the common colour-vision
// deficiencies), assigned by size: the smallest species dark blue, the largest light orange, others
// in between from the same palette. `diameters` in species order.
std::vector<Rgb> species_palette(std::span<const double> diameters);

// Speed colour map: viridis, from dark purple at 0 to yellow at `speed_max` (m/s) and above.
Rgb speed_colour(double speed, double speed_max);

struct PictureOptions {
  enum class Colour { Species, Speed };
  Colour colour = Colour::Species;
  int size = 800;            // pixels, width = height; the drum's diameter fills 96 % of it
  double speed_max = 0.5;    // m/s at the top of the speed colour map (seed 000 Fig. 6 uses 0.5)
  std::vector<Rgb> palette;  // per species, for Colour::Species
};

// What a picture reads; columns of the owned rows. `speed` is read only for Colour::Speed.
struct PictureGrains {
  std::span<const double> x, y, z, r;  // m
  std::span<const std::int32_t> type;  // species index
  std::span<const double> speed;       // m/s
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
  Rgb at(int px, int py) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(py) * width + px);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Pixel coordinates (x right, y down, pixel centres at +0.5) of a section point (u, v) in m.
struct PictureScale {
  double px_per_m = 0, cx = 0, cy = 0;
  double px(double u) const { return cx + u * px_per_m; }
  double py(double v) const { return cy - v * px_per_m; }
};
PictureScale picture_scale(const DrumSection& drum, int size);

// Renders the section. std::invalid_argument if the options or columns do not fit together
// (size outside [16, 8192], a species without a colour, missing speeds).
Image render_drum_picture(const PictureGrains& grains, const DrumSection& drum, const PictureOptions& options);

// Encodes 8-bit RGB PNG with tEXt entries (key, value) and writes it atomically (temporary, rename).
// std::runtime_error naming the file on any failure.
void write_png(const std::filesystem::path& file, const Image& image,
               const std::vector<std::pair<std::string, std::string>>& text = {});

// "pictures/angle_02.00.png": the picture file name for a rotation angle (rad), two decimals.
std::string picture_name(double angle);

}  // namespace gf
