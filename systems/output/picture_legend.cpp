#include "systems/output/picture_legend.hpp"

#include <cairo.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <numbers>
#include <stdexcept>

namespace gf {

namespace {

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

void set_colour(cairo_t* cr, const Rgb& c) { cairo_set_source_rgb(cr, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0); }

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

// Text with its left end at x and its baseline at y; returns its advance (px).
double text(cairo_t* cr, double x, double y, const std::string& s) {
  cairo_move_to(cr, x, y);
  cairo_show_text(cr, s.c_str());
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

// A number in at most four significant digits ("1.5", "0.25").
std::string short_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

double text_width(cairo_t* cr, const std::string& s) {
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

// A circular arrow of radius r about (cx, cy), three quarters of a turn, its head showing the sense
// (+1 counter-clockwise on the screen, whose y axis points down).
void turning_arrow(cairo_t* cr, double cx, double cy, double r, int sense, double line) {
  const double a0 = -0.25 * std::numbers::pi, sweep = 1.5 * std::numbers::pi;
  cairo_set_line_width(cr, line);
  cairo_new_path(cr);
  // On the screen, angles grow clockwise; counter-clockwise is the negative direction.
  if (sense > 0)
    cairo_arc_negative(cr, cx, cy, r, a0, a0 - sweep);
  else
    cairo_arc(cr, cx, cy, r, a0, a0 + sweep);
  cairo_stroke(cr);
  const double end = sense > 0 ? a0 - sweep : a0 + sweep;
  const double ex = cx + r * std::cos(end), ey = cy + r * std::sin(end);
  // The head points along the tangent in the direction of travel.
  const double tx = sense > 0 ? std::sin(end) : -std::sin(end), ty = sense > 0 ? -std::cos(end) : std::cos(end);
  const double h = 3.0 * line + 0.25 * r, nx = -ty, ny = tx;
  cairo_move_to(cr, ex + h * tx, ey + h * ty);
  cairo_line_to(cr, ex + 0.6 * h * nx, ey + 0.6 * h * ny);
  cairo_line_to(cr, ex - 0.6 * h * nx, ey - 0.6 * h * ny);
  cairo_close_path(cr);
  cairo_fill(cr);
}

// The species swatches, or the colour bar, from x along the baseline y.
void keys(cairo_t* cr, const PictureLegend& l, double x, double y, double font, double right) {
  if (l.bar_max > 0.0) {
    x += text(cr, x, y, "0") + 0.4 * font;
    const int w = std::max(
        4, static_cast<int>(right - x - text_width(cr, fixed(l.bar_max, 2) + " " + l.bar_unit) - 0.8 * font));
    for (int k = 0; k < w; ++k) {
      set_colour(cr, speed_colour(l.bar_max * k / (w - 1.0), l.bar_max));
      cairo_rectangle(cr, std::floor(x) + k, std::floor(y - 0.8 * font), 1.0, std::ceil(0.8 * font));
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, std::floor(x) + w + 0.4 * font, y, fixed(l.bar_max, 2) + " " + l.bar_unit);
    return;
  }
  // Entries wider than the room left of the scale bar (long names, size ranges) are set smaller to fit.
  double needed = 0.0;
  for (const PictureLegend::Entry& e : l.entries) needed += 2.4 * font + text_width(cr, e.label);
  if (needed > right - x && needed > 0.0) {
    font *= std::max(0.5, (right - x) / needed);
    cairo_set_font_size(cr, font);
  }
  for (const PictureLegend::Entry& e : l.entries) {
    set_colour(cr, e.colour);
    cairo_arc(cr, x + 0.4 * font, y - 0.35 * font, 0.4 * font, 0, 2 * std::numbers::pi);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    x += 1.2 * font;
    x += text(cr, x, y, e.label) + 1.2 * font;
  }
}

}  // namespace

int legend_band_height(int width) { return std::max(36, width / 9); }

double round_length(double target) {
  if (!(target > 0.0)) return 0.0;
  const double p = std::pow(10.0, std::floor(std::log10(target)));
  for (const double m : {5.0, 2.0, 1.0})
    if (m * p <= target) return m * p;
  return p;
}

std::string length_label(double m) {
  char buf[64];
  if (m >= 1.0)
    std::snprintf(buf, sizeof buf, "%g m", m);
  else if (m >= 1e-3)
    std::snprintf(buf, sizeof buf, "%g mm", m * 1e3);
  else
    std::snprintf(buf, sizeof buf, "%g um", m * 1e6);
  return buf;
}

Image annotate_picture(const Image& pic, const PictureLegend& l) {
  const int band = legend_band_height(pic.width);
  const int w = pic.width, h = pic.height + band;
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h), cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw std::runtime_error("picture legend: cairo cannot make a " + std::to_string(w) + " x " + std::to_string(h) +
                             " image");
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < h; ++y) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      if (y >= pic.height) {
        row[x] = 0xffffffu;
        continue;
      }
      const Rgb c = pic.at(x, y);
      row[x] = (std::uint32_t{c[0]} << 16) | (std::uint32_t{c[1]} << 8) | c[2];
    }
  }
  cairo_surface_mark_dirty(surface.get());
  {
    Context cr(cairo_create(surface.get()), cairo_destroy);
    cairo_select_font_face(cr.get(), "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    const double font = 0.25 * band, pad = 0.5 * font, line = std::max(1.5, w / 400.0);
    cairo_set_font_size(cr.get(), font);
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
    const double row1 = pic.height + 1.4 * font, row2 = pic.height + 3.0 * font;
    // Row 1: the time, the angle and the turning; the scale bar at the right.
    std::string first;
    if (std::isfinite(l.time)) first += "t = " + fixed(l.time, 3) + " s";
    if (std::isfinite(l.angle)) first += "   angle " + fixed(l.angle, 2) + " rad";
    if (l.turning != 0)
      first += std::string("   turning ") + (l.turning > 0 ? "counter-clockwise" : "clockwise") + " at " +
               short_text(l.omega) + " rad/s";
    text(cr.get(), pad, row1, first);
    double right = w - pad;
    if (l.px_per_m > 0.0) {
      const double metres = round_length(0.2 * w / l.px_per_m), px = metres * l.px_per_m;
      const std::string label = length_label(metres);
      const double x0 = w - pad - px;
      cairo_set_line_width(cr.get(), line);
      cairo_move_to(cr.get(), x0, row2 - 0.3 * font);
      cairo_line_to(cr.get(), x0 + px, row2 - 0.3 * font);
      for (const double x : {x0, x0 + px}) {
        cairo_move_to(cr.get(), x, row2 - 0.6 * font);
        cairo_line_to(cr.get(), x, row2);
      }
      cairo_stroke(cr.get());
      const double lw = text_width(cr.get(), label);
      text(cr.get(), x0 - lw - 0.4 * font, row2, label);
      right = x0 - lw - 1.5 * font;
    }
    // Row 2: the species or the colour bar.
    keys(cr.get(), l, pad, row2, font, right);
    // The arrow in the top-right corner, outside the drum (which fills 96 % of the width).
    if (l.turning != 0 && pic.height > 0) turning_arrow(cr.get(), w - 0.07 * w, 0.07 * w, 0.035 * w, l.turning, line);
  }
  cairo_surface_flush(surface.get());
  Image out;
  out.width = w, out.height = h;
  out.rgb.resize(3 * static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = &out.rgb[3 * (static_cast<std::size_t>(y) * w + x)];
      p[0] = static_cast<std::uint8_t>(row[x] >> 16), p[1] = static_cast<std::uint8_t>(row[x] >> 8),
      p[2] = static_cast<std::uint8_t>(row[x]);
    }
  }
  return out;
}

}  // namespace gf
