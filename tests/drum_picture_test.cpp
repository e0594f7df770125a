// Drum pictures: rendered, encoded, read back with libpng, and checked pixel by pixel at known
// places (disc centres, outside the drum, the outline); the projection and draw order; and the
// observer that draws them at requested rotation angles in a real run.
#include "systems/output/drum_picture.hpp"
#include "systems/output/picture_legend.hpp"

#include <png.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "systems/fill/state_csv.hpp"
#include "systems/output/dem_observers.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using gf::Rgb;
using gf::test::TempDir;

namespace {

struct Png {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  Rgb at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

// Decoded by libpng's simplified reader into 8-bit RGB; fails the test if it cannot be read.
Png read_png(const fs::path& file) {
  png_image img{};
  img.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&img, file.c_str()) != 0);
  img.format = PNG_FORMAT_RGB;
  Png out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.rgb.resize(PNG_IMAGE_SIZE(img));
  REQUIRE(png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr) != 0);
  return out;
}

gf::DrumSection drum(const gf::Vec3d& axis, const gf::Vec3d& gravity, double radius = 0.05) {
  gf::Wall w;
  w.kind = gf::Wall::Kind::CylinderInner;
  w.cur_center = {0.01, 0.02, 0.03};
  w.cur_axis = axis;
  w.radius = radius;
  return gf::drum_section(w, gravity);
}

struct Grains {
  std::vector<double> x, y, z, r, speed;
  std::vector<std::int32_t> type;
  void add(double px, double py, double pz, double rad, std::int32_t t, double v = 0) {
    x.push_back(px), y.push_back(py), z.push_back(pz), r.push_back(rad), type.push_back(t), speed.push_back(v);
  }
  gf::PictureGrains view() const { return {x, y, z, r, type, speed}; }
};

// Pixel holding the section point (u, v) m.
std::pair<int, int> pixel(const gf::DrumSection& d, int size, double u, double v) {
  const gf::PictureScale s = gf::picture_scale(d, size);
  return {static_cast<int>(std::floor(s.px(u))), static_cast<int>(std::floor(s.py(v)))};
}

const std::vector<double> kDiameters{1e-3, 3e-3};  // species 0 small, 1 large

gf::PictureOptions species_options(int size) {
  gf::PictureOptions o;
  o.size = size;
  o.palette = gf::species_palette(kDiameters);
  return o;
}

}  // namespace

TEST_CASE("picture: discs at their projected place and size, the drum outline, white outside", "[picture]") {
  TempDir dir("picture");
  const gf::DrumSection d = drum({0, 0, 1}, {0, -9.81, 0});
  Grains g;
  // Centre (0.01, 0.02, 0.03): a large disc right of and below the axis, a small one up left.
  g.add(0.01 + 0.02, 0.02 - 0.01, 0.03, 5e-3, 1);
  g.add(0.01 - 0.02, 0.02 + 0.03, 0.03, 2e-3, 0);
  const int size = 400;
  const fs::path file = dir.path / "p.png";
  gf::write_png(file, gf::render_drum_picture(g.view(), d, species_options(size)));
  const Png img = read_png(file);
  REQUIRE(img.width == size);
  REQUIRE(img.height == size);
  const auto palette = gf::species_palette(kDiameters);
  // At a disc centre the pixel is wholly inside the disc (radius >= 7 px here), so anti-aliasing
  // leaves the exact palette colour: compare exactly.
  const auto [lx, ly] = pixel(d, size, 0.02, -0.01);
  CHECK(img.at(lx, ly) == palette[1]);
  const auto [sx, sy] = pixel(d, size, -0.02, 0.03);
  CHECK(img.at(sx, sy) == palette[0]);
  // True radius: 1.5 px inside the rim is still the grain's colour, 1.5 px outside is the drum's
  // inside (the anti-aliasing ramp is one pixel wide, so 1.5 px clears it with pixel rounding).
  const double rpx = 5e-3 * gf::picture_scale(d, size).px_per_m;
  CHECK(img.at(lx + static_cast<int>(rpx - 1.5), ly) == palette[1]);
  const Rgb inside{232, 232, 232}, white{255, 255, 255}, black{0, 0, 0};
  CHECK(img.at(lx + static_cast<int>(rpx + 1.5), ly) == inside);
  // The axis (empty here) is the drum's inside; corners are outside the drum: white.
  const auto [cx, cy] = pixel(d, size, 0, 0);
  CHECK(img.at(cx, cy) == inside);
  CHECK(img.at(1, 1) == white);
  CHECK(img.at(size - 2, size - 2) == white);
  // The outline: a black ring of 2 px just outside the radius (96 % of the width).
  const double rd = 0.05 * gf::picture_scale(d, size).px_per_m;
  CHECK(img.at(cx + static_cast<int>(std::lround(rd + 1.0)), cy) == black);
  CHECK(img.at(cx, cy - static_cast<int>(std::lround(rd + 1.0))) == black);
}

TEST_CASE("picture: gravity points down the image whatever the axis", "[picture]") {
  // Axis x, gravity -z: up is +z, right is up x axis = +y.
  const gf::DrumSection d = drum({1, 0, 0}, {0, 0, -9.81});
  Grains g;
  g.add(0.01, 0.02, 0.03 + 0.03, 3e-3, 0);  // above the axis
  g.add(0.01, 0.02 + 0.03, 0.03, 3e-3, 1);  // right of it
  const int size = 200;
  const gf::Image img = gf::render_drum_picture(g.view(), d, species_options(size));
  const auto palette = gf::species_palette(kDiameters);
  CHECK(img.at(size / 2, static_cast<int>(size / 2 - 0.03 * gf::picture_scale(d, size).px_per_m)) == palette[0]);
  CHECK(img.at(static_cast<int>(size / 2 + 0.03 * gf::picture_scale(d, size).px_per_m), size / 2) == palette[1]);
}

TEST_CASE("picture: the nearest grain along the axis is drawn last, whatever the row order", "[picture]") {
  const gf::DrumSection d = drum({0, 0, 1}, {0, -9.81, 0});
  const auto palette = gf::species_palette(kDiameters);
  for (int near_first : {0, 1}) {
    Grains g;
    // Same section point; the large grain is nearer the viewer (larger z along the +z axis).
    if (near_first) g.add(0.01, 0.0, 0.033, 4e-3, 1);
    g.add(0.01, 0.0, 0.027, 4e-3, 0);
    if (!near_first) g.add(0.01, 0.0, 0.033, 4e-3, 1);
    const gf::Image img = gf::render_drum_picture(g.view(), d, species_options(200));
    const auto [px, py] = pixel(d, 200, 0.0, -0.02);
    CHECK(img.at(px, py) == palette[1]);
  }
}

TEST_CASE("picture: speed colours run from viridis' dark end at rest to its yellow end at speed_max", "[picture]") {
  const gf::DrumSection d = drum({0, 0, 1}, {0, -9.81, 0});
  Grains g;
  g.add(0.01 - 0.02, 0.02, 0.03, 3e-3, 0, 0.0);
  g.add(0.01 + 0.02, 0.02, 0.03, 3e-3, 0, 0.9);  // above speed_max: clamped
  g.add(0.01, 0.02 - 0.02, 0.03, 3e-3, 1, 0.25);
  gf::PictureOptions o;
  o.size = 300;
  o.colour = gf::PictureOptions::Colour::Speed;
  o.speed_max = 0.5;
  const gf::Image img = gf::render_drum_picture(g.view(), d, o);
  auto at = [&](double u, double v) {
    const auto [px, py] = pixel(d, 300, u, v);
    return img.at(px, py);
  };
  CHECK(at(-0.02, 0) == Rgb{68, 1, 84});
  CHECK(at(0.02, 0) == Rgb{253, 231, 37});
  CHECK(at(0, -0.02) == Rgb{33, 144, 141});  // half of speed_max: viridis' middle
  CHECK(gf::speed_colour(0.25, 0.5) == Rgb{33, 144, 141});
}

TEST_CASE("picture: species palette is by size, small dark, large light, distinct", "[picture]") {
  auto luminance = [](const Rgb& c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; };
  const std::vector<double> big_first{3e-3, 1e-3};
  const auto p = gf::species_palette(big_first);
  CHECK(luminance(p[1]) < luminance(p[0]));
  CHECK(p == std::vector<Rgb>{gf::species_palette(kDiameters)[1], gf::species_palette(kDiameters)[0]});
  const auto four = gf::species_palette(std::vector<double>{1e-3, 2e-3, 3e-3, 4e-3});
  for (std::size_t a = 0; a < four.size(); ++a)
    for (std::size_t b = a + 1; b < four.size(); ++b) CHECK(four[a] != four[b]);
}

TEST_CASE("picture: file names and errors", "[picture]") {
  CHECK(gf::picture_name(2.0) == "angle_02.00.png");
  CHECK(gf::picture_name(30.0) == "angle_30.00.png");
  CHECK(gf::picture_name(123.456) == "angle_123.46.png");
  TempDir dir("picture_err");
  const fs::path missing = dir.path / "no" / "such" / "p.png";
  gf::Image img;
  img.width = img.height = 4;
  img.rgb.assign(48, 0);
  CHECK_THROWS_WITH(gf::write_png(missing, img), Catch::Contains(missing.string()));
  gf::Image bad = img;
  bad.rgb.resize(10);
  CHECK_THROWS_WITH(gf::write_png(dir.path / "bad.png", bad), Catch::Contains("bad.png"));
  const gf::DrumSection d = drum({0, 0, 1}, {0, -9.81, 0});
  Grains g;
  g.add(0, 0, 0, 1e-3, 2);  // no colour for species 2
  CHECK_THROWS_AS(gf::render_drum_picture(g.view(), d, species_options(100)), std::invalid_argument);
  gf::PictureOptions tiny = species_options(8);
  CHECK_THROWS_AS(gf::render_drum_picture(Grains{}.view(), d, tiny), std::invalid_argument);
}

TEST_CASE("picture: the shared settled drum, 47,108 grains at 800 px", "[picture]") {
  const auto rows = gf::read_state_csv(fs::path(GRAINFLOW_SOURCE_DIR) / "scenes/data/drum_settled_47108.csv");
  Grains g;
  for (const auto& row : rows) g.add(row.x[0], row.x[1], row.x[2], 0.5 * row.diameter, row.type - 1);
  gf::Wall w;
  w.kind = gf::Wall::Kind::CylinderInner;
  w.radius = 0.075;
  const gf::DrumSection d = gf::drum_section(w, {0, -9.81, 0});
  TempDir dir("picture_settled");
  const fs::path file = dir.path / gf::picture_name(0.0);
  const auto t0 = std::chrono::steady_clock::now();
  gf::write_png(file, gf::render_drum_picture(g.view(), d, species_options(800)));
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  WARN("rendering and writing 47,108 grains at 800 px: " << ms << " ms, " << fs::file_size(file) << " bytes");
  const Png img = read_png(file);
  REQUIRE(img.width == 800);
  // The bed is in the lower half: the bottom of the drum, just inside the wall, is covered by grains
  // (small or large colour), and the top of the drum, just inside the wall, is empty.
  const auto palette = gf::species_palette(kDiameters);
  std::size_t bed = 0, top = 0, samples = 0;
  for (int dx = -40; dx <= 40; ++dx, ++samples) {
    const auto [bx, by] = pixel(d, 800, dx * 1e-4, -0.070);
    const Rgb b = img.at(bx, by);
    bed += b == palette[0] || b == palette[1] || (b[0] != b[1] || b[1] != b[2]);  // grain colour or a blend of two
    const auto [tx, ty] = pixel(d, 800, dx * 1e-4, 0.070);
    top += img.at(tx, ty) == Rgb{232, 232, 232};
  }
  // Packed at ~0.6 solid fraction in a thin (8 mm) drum, most lines of sight hit a grain: 90 %.
  CHECK(bed >= 9 * samples / 10);
  CHECK(top == samples);
}

namespace {

// A 40 mm drum turning at 10 rad/s with 200 small and 30 large grains poured at random (SI units):
// 1.5 ms of run is 0.015 rad, enough to pass the second requested angle and not the third.
const std::string kDrumScene = R"([run]
dt = 1.0e-5
duration = 0.01
skin = 1.0e-4
[[species]]
name = "small"
diameter = 1.0e-3
density = 2500.0
[[species]]
name = "large"
diameter = 2.0e-3
density = 2500.0
[contact]
model = "linear_spring_dashpot"
kn = 1000.0
kt = 600.0
en = 0.3
et = 0.3
friction = 0.3
[[wall]]
type = "drum"
center = [0.0, 0.0, 0.0]
axis = [0.0, 0.0, 1.0]
radius = 0.02
length = 0.006
omega = 10.0
[[fill]]
kind = "random"
region = { shape = "cylinder", center = [0.0, 0.0, 0.0], axis = [0.0, 0.0, 1.0], radius = 0.018, length = 0.004 }
count = { small = 200, large = 30 }
[output]
series_interval = 1.0e-4
picture_angles = [0.0, 0.01, 5.0]
picture_size = 64
)";

}  // namespace

TEST_CASE("picture: a run draws each requested angle once it is reached, and reports the pattern", "[picture][cli]") {
  REQUIRE(fs::exists(GRAINFLOW_BINARY));
  TempDir dir("picture_run");
  const fs::path scene = dir.write("drum.toml", kDrumScene), out = dir.path / "out";
  for (const char* colour : {"species", "speed"}) {
    INFO("colour " << colour);
    const std::string cmd = std::string("'") + GRAINFLOW_BINARY + "' run '" + scene.string() + "' --out '" +
                            out.string() + "' --steps 150 --threads 1 --quiet --set output.picture_colour=\\\"" +
                            colour + "\\\" > /dev/null 2>&1";
    REQUIRE(std::system(cmd.c_str()) == 0);
    CHECK(fs::exists(out / "pictures" / "angle_00.00.png"));
    CHECK(fs::exists(out / "pictures" / "angle_00.01.png"));
    CHECK_FALSE(fs::exists(out / "pictures" / "angle_05.00.png"));  // 5 rad is never reached
    const Png img = read_png(out / "pictures" / "angle_00.01.png");
    CHECK(img.width == 64);
    CHECK(img.height == 64 + gf::legend_band_height(64));  // the legend band below the drum
    CHECK(img.at(0, 0) == Rgb{255, 255, 255});
    const auto summary = nlohmann::json::parse(gf::test::read_file(out / "summary.json"));
    CHECK(summary.at("pictures") == 2);
    // A drum with two species carries the pattern columns and final values; 230 grains are too
    // few for the classifier, so it must not claim a pattern.
    const auto final_values = summary.at("final");
    CHECK(final_values.at("pattern") == "undecided");
    CHECK(final_values.at("petals") == 0);
    const auto rows = gf::test::read_lines(out / "series.csv");
    REQUIRE(rows.size() > 1);
    CHECK(rows[0].ends_with(",segregation_index,lacey_index,lacey_cell_grains,pattern,petals,pattern_contrast,"
                            "surface_angle,radial_segregation,depth_segregation"));
    fs::remove_all(out);
  }
}

TEST_CASE("picture: an interval draws every multiple once, named after the multiple", "[picture]") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(kDrumScene);
  TempDir dir("picture_interval");
  gf::PictureSettings ps;
  ps.dir = dir.path / "pictures";
  ps.interval = 0.01;  // rad; at 10 rad/s and dt = 1e-5 s, one picture every 100 steps
  ps.options.size = 32;
  ps.options.palette = gf::species_palette(kDiameters);
  gf::PictureOutput pics(ps);
  gf::World& w = sim.world();
  pics.run(w, gf::next_step(w.clock));  // angle 0
  pics.run(w, gf::next_step(w.clock));  // the same state again: nothing new is due
  CHECK(pics.pictures() == 1);
  sim.advance(99);  // 0.0099 rad: the next multiple not yet reached
  pics.run(w, gf::next_step(w.clock));
  CHECK(pics.pictures() == 1);
  sim.advance(1);  // 0.01 rad, up to the clock's round-off
  pics.run(w, gf::next_step(w.clock));
  sim.advance(100);
  pics.run(w, gf::next_step(w.clock));
  CHECK(pics.pictures() == 3);
  for (const char* name : {"angle_00.00.png", "angle_00.01.png", "angle_00.02.png"}) {
    INFO(name);
    CHECK(read_png(ps.dir / name).width == 32);
  }
}
