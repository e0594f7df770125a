#include "systems/output/drum_picture.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <numeric>
#include <stdexcept>

#include "engine/atomic_file.hpp"

namespace gf {

namespace {

// Okabe & Ito (2008), "Color Universal Design": blue, sky blue, bluish green, vermillion, reddish
// purple, then orange for the largest species.
constexpr Rgb kBlue{0, 114, 178}, kOrange{230, 159, 0};
constexpr std::array<Rgb, 4> kMiddle{{{86, 180, 233}, {0, 158, 115}, {213, 94, 0}, {204, 121, 167}}};

constexpr Rgb kOutside{255, 255, 255}, kInside{232, 232, 232}, kOutline{0, 0, 0};

// viridis (matplotlib) at nine equally spaced points.
constexpr std::array<Rgb, 9> kViridis{{{68, 1, 84},
                                       {71, 44, 122},
                                       {59, 81, 139},
                                       {44, 113, 142},
                                       {33, 144, 141},
                                       {39, 173, 129},
                                       {92, 200, 99},
                                       {170, 220, 50},
                                       {253, 231, 37}}};

// Coverage of a pixel whose centre is at distance d from an edge at distance `edge`, inside being
// d < edge: a one-pixel linear ramp, the usual cheap anti-aliasing.
inline double coverage(double d, double edge) { return std::clamp(edge + 0.5 - d, 0.0, 1.0); }

void draw_disc(Image& img, double cx, double cy, double rp, const Rgb& c) {
  const int x0 = std::max(0, static_cast<int>(std::floor(cx - rp - 1))),
            x1 = std::min(img.width - 1, static_cast<int>(std::ceil(cx + rp + 1)));
  const int y0 = std::max(0, static_cast<int>(std::floor(cy - rp - 1))),
            y1 = std::min(img.height - 1, static_cast<int>(std::ceil(cy + rp + 1)));
  for (int py = y0; py <= y1; ++py)
    for (int px = x0; px <= x1; ++px) {
      const double dx = px + 0.5 - cx, dy = py + 0.5 - cy;
      const double a = coverage(std::sqrt(dx * dx + dy * dy), rp);
      if (a > 0.0) blend(&img.rgb[3 * (static_cast<std::size_t>(py) * img.width + px)], c, a);
    }
}

struct PngSink {
  std::string bytes;
  char error[256] = "unknown libpng error";
};

void png_fail(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->error, sizeof sink->error, "%s", msg);
  png_longjmp(png, 1);
}
void png_warn(png_structp, png_const_charp) {}
void png_put(png_structp png, png_bytep data, png_size_t n) {
  static_cast<PngSink*>(png_get_io_ptr(png))->bytes.append(reinterpret_cast<const char*>(data), n);
}
void png_flush_none(png_structp) {}

// Kept free of C++ objects with destructors between setjmp and any longjmp back to it.
bool encode_png(const Image& img, png_text* text, int n_text, PngSink& sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, png_fail, png_warn);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &sink, png_put, png_flush_none);
  png_set_IHDR(png, info, static_cast<png_uint_32>(img.width), static_cast<png_uint_32>(img.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (n_text > 0) png_set_text(png, info, text, n_text);
  png_write_info(png, info);
  for (int y = 0; y < img.height; ++y)
    png_write_row(png, const_cast<png_bytep>(img.rgb.data() + 3 * static_cast<std::size_t>(y) * img.width));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::vector<Rgb> species_palette(std::span<const double> diameters) {
  const std::size_t n = diameters.size();
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return diameters[a] < diameters[b]; });
  std::vector<Rgb> out(n, kBlue);
  for (std::size_t rank = 0; rank < n; ++rank) {
    Rgb c = kMiddle[(rank - 1) % kMiddle.size()];
    if (rank == 0)
      c = kBlue;
    else if (rank == n - 1)
      c = kOrange;
    out[order[rank]] = c;
  }
  return out;
}

Rgb speed_colour(double speed, double speed_max) {
  const double t = std::clamp(speed_max > 0 ? speed / speed_max : 0.0, 0.0, 1.0) * (kViridis.size() - 1);
  const std::size_t i = std::min(static_cast<std::size_t>(t), kViridis.size() - 2);
  const double f = t - static_cast<double>(i);
  Rgb c;
  for (int k = 0; k < 3; ++k)
    c[k] = static_cast<std::uint8_t>(std::lround((1 - f) * kViridis[i][k] + f * kViridis[i + 1][k]));
  return c;
}

PictureScale picture_scale(const DrumSection& drum, int size) {
  PictureScale s;
  s.px_per_m = 0.96 * size / (2.0 * drum.radius);
  s.cx = s.cy = 0.5 * size;
  return s;
}

Image render_drum_picture(const PictureGrains& g, const DrumSection& drum, const PictureOptions& opt) {
  if (opt.size < 16 || opt.size > 8192)
    throw std::invalid_argument("picture size " + std::to_string(opt.size) + " px is outside [16, 8192]");
  if (!(drum.radius > 0)) throw std::invalid_argument("picture of a drum needs a positive radius");
  const std::size_t n = g.x.size();
  const bool by_speed = opt.colour == PictureOptions::Colour::Speed;
  if (g.y.size() != n || g.z.size() != n || g.r.size() != n || g.type.size() != n || (by_speed && g.speed.size() != n))
    throw std::invalid_argument("picture columns differ in length (speeds are needed when colouring by speed)");

  Image img;
  img.width = img.height = opt.size;
  img.rgb.assign(3 * static_cast<std::size_t>(opt.size) * opt.size, 0);
  const PictureScale sc = picture_scale(drum, opt.size);
  const double rd = drum.radius * sc.px_per_m;
  for (int py = 0; py < img.height; ++py)
    for (int px = 0; px < img.width; ++px) {
      std::uint8_t* p = &img.rgb[3 * (static_cast<std::size_t>(py) * img.width + px)];
      const double dx = px + 0.5 - sc.cx, dy = py + 0.5 - sc.cy;
      std::copy(kOutside.begin(), kOutside.end(), p);
      blend(p, kInside, coverage(std::sqrt(dx * dx + dy * dy), rd));
    }

  // Far grains first: the viewer looks down -axis, so a larger depth is nearer.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::vector<double> depth(n);
  for (std::size_t i = 0; i < n; ++i) depth[i] = drum.depth(g.x[i], g.y[i], g.z[i]);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return depth[a] < depth[b]; });
  for (const std::uint32_t i : order) {
    Rgb c;
    if (by_speed) {
      c = speed_colour(g.speed[i], opt.speed_max);
    } else {
      const std::int32_t t = g.type[i];
      if (t < 0 || static_cast<std::size_t>(t) >= opt.palette.size())
        throw std::invalid_argument("picture: species " + std::to_string(t) + " has no colour in the palette");
      c = opt.palette[t];
    }
    draw_disc(img, sc.px(drum.u(g.x[i], g.y[i], g.z[i])), sc.py(drum.v(g.x[i], g.y[i], g.z[i])), g.r[i] * sc.px_per_m,
              c);
  }

  // The drum's inner circle on top, a ring just outside the wall so it hides no grain.
  const double w = std::max(2.0, opt.size / 400.0);
  for (int py = 0; py < img.height; ++py)
    for (int px = 0; px < img.width; ++px) {
      const double dx = px + 0.5 - sc.cx, dy = py + 0.5 - sc.cy;
      const double d = std::abs(std::sqrt(dx * dx + dy * dy) - (rd + 0.5 * w));
      const double a = coverage(d, 0.5 * w);
      if (a > 0.0) blend(&img.rgb[3 * (static_cast<std::size_t>(py) * img.width + px)], kOutline, a);
    }
  return img;
}

void write_png(const std::filesystem::path& file, const Image& image,
               const std::vector<std::pair<std::string, std::string>>& text) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != 3 * static_cast<std::size_t>(image.width) * image.height)
    throw std::runtime_error("cannot write picture '" + file.string() + "': the image is empty or malformed");
  std::vector<png_text> entries(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    entries[i] = png_text{};
    entries[i].compression = PNG_TEXT_COMPRESSION_NONE;
    entries[i].key = const_cast<char*>(text[i].first.c_str());
    entries[i].text = const_cast<char*>(text[i].second.c_str());
    entries[i].text_length = text[i].second.size();
  }
  PngSink sink;
  sink.bytes.reserve(image.rgb.size() / 4);
  if (!encode_png(image, entries.data(), static_cast<int>(entries.size()), sink))
    throw std::runtime_error("cannot encode picture '" + file.string() + "': " + sink.error);
  write_file_atomic(file, sink.bytes);
}

std::string picture_name(double angle) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "angle_%05.2f.png", std::abs(angle));
  return buf;
}

}  // namespace gf
