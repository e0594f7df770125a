// Side views of composite grains: a dilated member is drawn as the projection of its core grown by
// r (a 20 x 10 mm box core with r = 2 mm covers 24 x 14 mm of the picture), in its body's colour,
// fixed bodies grey, removed bodies not at all, nearer members over further ones.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "systems/bodies/bodies.hpp"
#include "systems/output/body_picture.hpp"

namespace {

// A body at x with one box member of core half-sizes h and dilation r.
void add_box(gf::Bodies& b, gf::Members& m, const std::array<double, 3>& x, const Eigen::Vector3d& h, double r,
             gf::Motion motion = gf::Motion::moving) {
  gf::BodyRow row;
  row.x = x;
  row.mass = 1.0;
  row.inertia = {1.0, 1.0, 1.0};
  row.motion = motion;
  const auto body = static_cast<std::uint32_t>(b.push(row));
  gf::MemberRow mr;
  mr.body = body;
  mr.radius = r;
  for (int k = 0; k < 8; ++k)
    mr.vertices.push_back({(k & 1 ? 1 : -1) * h.x(), (k & 2 ? 1 : -1) * h.y(), (k & 4 ? 1 : -1) * h.z()});
  m.push(mr);
}

// The pixel at world point (u, v) of the view (its right and up axes).
gf::Rgb at(const gf::Image& img, const gf::BodyView& v, double u, double w) {
  const double s = v.size / std::max(v.hi[v.right] - v.lo[v.right], v.hi[v.up] - v.lo[v.up]);
  const int px = static_cast<int>((u - v.lo[v.right]) * s), py = img.height - 1 - static_cast<int>((w - v.lo[v.up]) * s);
  return img.at(px, py);
}

}  // namespace

TEST_CASE("body picture: a dilated box's silhouette, grey fixed bodies, removed ones left out, nearest on top") {
  gf::Bodies b;
  gf::Members m;
  add_box(b, m, {0.0, 0.0, 0.0}, {0.010, 0.005, 0.005}, 0.002);                         // 24 x 14 mm seen along z
  add_box(b, m, {0.0, -0.03, 0.0}, {0.03, 0.002, 0.01}, 0.001, gf::Motion::fixed);      // a floor
  add_box(b, m, {0.05, 0.0, 0.0}, {0.005, 0.005, 0.005}, 0.001, gf::Motion::removed);  // a gate, gone
  add_box(b, m, {0.0, 0.0, 0.02}, {0.002, 0.002, 0.002}, 0.0);                          // small, in front
  gf::place_members(b, m);
  gf::BodyView v;
  v.view = 2, v.right = 0, v.up = 1, v.size = 1000;
  v.lo = {-0.05, -0.05, -0.05};
  v.hi = {0.05, 0.05, 0.05};
  const std::vector<gf::Rgb> colour{{0, 114, 178}, {1, 2, 3}, {9, 9, 9}, {213, 94, 0}};
  const gf::Image img = gf::render_body_picture(b, m, colour, v);
  REQUIRE(img.width == 1000);
  REQUIRE(img.height == 1000);
  const gf::Rgb white{255, 255, 255};
  // Inside the silhouette (|x| < 12 mm, |y| < 7 mm) the body's blue, shaded (it is the furthest
  // member, at 0.6 of its colour), outside white: the edge at 12 mm lies within a pixel (0.1 mm).
  const gf::Rgb inside = at(img, v, 0.008, 0.004);
  CHECK(inside[2] > inside[0]);
  CHECK(inside != white);
  CHECK(at(img, v, 0.0118, 0.0) != white);
  CHECK(at(img, v, 0.0123, 0.0) == white);
  CHECK(at(img, v, 0.0, 0.0068) != white);
  CHECK(at(img, v, 0.0, 0.0073) == white);
  // The rounded corner: the core's corner (10, 5) mm grown by 2 mm reaches (11.4, 6.4) mm, not (11.9, 6.9).
  CHECK(at(img, v, 0.0113, 0.0063) != white);
  CHECK(at(img, v, 0.0118, 0.0068) == white);
  // The fixed floor grey whatever its colour entry; the removed gate not drawn.
  const gf::Rgb floor = at(img, v, -0.02, -0.03);
  CHECK(floor[0] == floor[1]);
  CHECK(floor[1] == floor[2]);
  CHECK(floor[0] > 60);
  CHECK(at(img, v, 0.05, 0.0) == white);
  // The small box in front (z = 20 mm) covers the large one: vermillion at the centre.
  const gf::Rgb front = at(img, v, 0.0005, 0.0005);
  CHECK(front[0] > front[2]);
  // Windows and colours that do not fit are refused.
  CHECK_THROWS_AS(gf::render_body_picture(b, m, {colour[0]}, v), std::invalid_argument);
  gf::BodyView flat = v;
  flat.hi[1] = flat.lo[1];
  CHECK_THROWS_AS(gf::render_body_picture(b, m, colour, flat), std::invalid_argument);
  // body_view frames every body that is not removed, with a margin.
  const gf::BodyView framed = gf::body_view(b, m, 2, 800, std::nan(""));
  CHECK(framed.hi[0] < 0.05);  // the removed gate at x = 50 mm is not framed
  CHECK(framed.lo[1] < -0.032);
}

TEST_CASE("body picture: file names carry the time to four decimals, and layers alternate two colours") {
  CHECK(gf::body_picture_name(1.25) == "time_0001.2500.png");
  CHECK(gf::body_picture_name(0.0) == "time_0000.0000.png");
  CHECK(gf::layer_colour(0) == gf::layer_colour(2));
  CHECK(gf::layer_colour(0) != gf::layer_colour(1));
  CHECK(gf::group_colour(0) == gf::layer_colour(0));
  CHECK(gf::group_colour(7) == gf::group_colour(0));
}
