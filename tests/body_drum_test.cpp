// Composite grains in drums (member_cylinder, BodyPlane with `cylinder` and `omega`): the contact of
// a member with the inside of a cylinder against closed forms, a box coming to rest on the curved
// mantle of a drum at the height its closed form gives, and a box carried up by a turning drum to
// the angle where friction just holds it, tan(theta) = mu. Bad walls are refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include <Eigen/Geometry>

#include "systems/bodies/bodies.hpp"
#include "systems/bodies/member_geometry.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

using Eigen::Vector3d;

constexpr double kR = 0.05;       // m, the drum's radius
constexpr double kDil = 0.001;    // m, the box's dilation
constexpr double kCx = 0.005, kCy = 0.004, kCz = 0.003;  // m, the core's half edges (outer 12 x 10 x 8 mm)

std::string scene(double omega, double friction, double duration) {
  return "[run]\ndt = 2.0e-5\nduration = " + std::to_string(duration) + "\nskin = 1.0e-3\ngravity = [0.0, -9.81, 0.0]\n\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1.0e4\nkt = 1.0e4\nkr = 0.0\nen = 0.3\net = 0.3\ner = 0.3\n"
         "friction = " + std::to_string(friction) + "\nrolling_friction = 0.0\n\n"
         "[contact.wall]\nfriction = " + std::to_string(friction) + "\n\n"
         "[[wall]]\ntype = \"drum\"\ncenter = [0.0, 0.0, 0.0]\naxis = [0.0, 0.0, 1.0]\nradius = 0.05\nlength = 0.03\n"
         "omega = " + std::to_string(omega) + "\n\n"
         "[[shape]]\nname = \"box\"\nkind = \"box\"\nsize = [0.012, 0.010, 0.008]\nradius = 0.001\ndensity = 2500.0\n\n"
         "[[bodies]]\nshape = \"box\"\npositions = [[0.0, -0.035, 0.0]]\n";
}

std::string load_error(const std::string& text) {
  return gf::test::scene_error_of([&] { gf::DemSimulation::from_text(text); });
}

}  // namespace

TEST_CASE("member_cylinder: a point member and a box across the mantle against closed forms") {
  // A sphere (a point core of r = 2 mm) at 49 mm from the axis, 45 degrees round: 1 mm through.
  const double a = std::numbers::pi / 4, r = 0.002;
  const gf::CorePoints point(std::vector<Vector3d>{Vector3d::Zero()});
  const Vector3d at(0.049 * std::cos(a), 0.049 * std::sin(a), 0.007);
  const gf::MemberContact s = gf::member_cylinder(gf::posed_member(point, r, at, Eigen::Matrix3d::Identity()),
                                                  Vector3d::Zero(), Vector3d::UnitZ(), kR);
  REQUIRE(s.touching());
  CHECK(s.delta == Approx(0.001).margin(1e-15));
  CHECK((s.n - Vector3d(std::cos(a), std::sin(a), 0)).norm() < 1e-15);
  CHECK((s.point - (at + (r - 0.0005) * s.n)).norm() < 1e-15);
  // A box face down across the bottom of the mantle: its four lowest vertices, at x = +-cx, reach
  // rho = sqrt(cx^2 + (Y + cy)^2); by symmetry the normal is straight down and the point below the centre.
  const double Y = 0.045;
  std::vector<Vector3d> corners;
  for (double x : {-kCx, kCx})
    for (double y : {-kCy, kCy})
      for (double z : {-kCz, kCz}) corners.emplace_back(x, y, z);
  const gf::CorePoints box(corners);
  const gf::MemberContact b = gf::member_cylinder(
      gf::posed_member(box, kDil, Vector3d(0, -Y, 0), Eigen::Matrix3d::Identity()), Vector3d::Zero(), Vector3d::UnitZ(), kR);
  REQUIRE(b.touching());
  CHECK(b.delta == Approx(std::hypot(kCx, Y + kCy) + kDil - kR).margin(1e-15));
  CHECK((b.n - Vector3d(0, -1, 0)).norm() < 1e-15);
  CHECK(std::abs(b.point.x()) < 1e-15);
  // Well inside: apart.
  CHECK_FALSE(gf::member_cylinder(gf::posed_member(box, kDil, Vector3d(0, -0.02, 0), Eigen::Matrix3d::Identity()),
                                  Vector3d::Zero(), Vector3d::UnitZ(), kR)
                  .touching());
}

TEST_CASE("a box rests face down on the bottom of a drum's curved mantle") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene(0.0, 0.5, 0.4));
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const gf::MemberShape m = gf::member_shape(b, sim.world().tables.get<gf::Members>(), 0);
  // At rest on its two lower long edges, one contact of depth delta = m g / kn: those edges at
  // rho = R - r + delta from the axis, at x = +-cx, so at y = -sqrt((R - r + delta)^2 - cx^2). (The
  // core's vertices, not the centre of mass, whose place in the box carries the voxel grid's error.)
  const double delta = b.mass.m[0] * 9.81 / 1.0e4;
  const double lowest = -std::sqrt((kR - kDil + delta) * (kR - kDil + delta) - kCx * kCx);
  double low = 0, left = 0, right = 0;
  for (std::size_t i = 0; i < m.vertices(); ++i) {
    low = std::min(low, m.vertex(i).y());
    left = std::min(left, m.vertex(i).x());
    right = std::max(right, m.vertex(i).x());
  }
  INFO("lowest vertices at y " << low << " m, expected " << lowest << "; x from " << left << " to " << right);
  CHECK(std::abs(left + right) < 1e-9);                // centred on the bottom
  CHECK(low == Approx(lowest).margin(1e-9));           // the damped spring's settling leaves below a nanometre
}

TEST_CASE("a turning drum carries a box up to where friction just holds it, tan(theta) = mu") {
  // Turning at 1 rad/s about +z, the mantle's bottom moves towards +x: the box rides up that side
  // until the wall slides under it, where the tangential weight balances mu times the normal load:
  // the contact normal at theta = atan(mu) from straight down. The box does not settle there: it
  // sticks, rides past, slips back (stick-slip, the normal swinging about +-5 degrees with a period
  // near 0.8 s); so the normal's angle is averaged over 1 to 5 s, about five swings, every 1 ms,
  // and held to 1 degree, a fifth of the swing. (It does not topple: tan(theta) < (cx + r) / (cy + r).)
  const double mu = 0.5;
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene(1.0, mu, 5.0));
  sim.advance(50000);  // 1 s
  double sum = 0;
  int samples = 0;
  for (int k = 0; k < 4000; ++k) {
    sim.advance(50);  // 1 ms
    const gf::MemberContact c = gf::member_cylinder(
        gf::member_shape(sim.world().tables.get<gf::Bodies>(), sim.world().tables.get<gf::Members>(), 0),
        Vector3d::Zero(), Vector3d::UnitZ(), kR);
    if (!c.touching()) continue;
    sum += std::atan2(c.n.x(), -c.n.y());
    ++samples;
  }
  REQUIRE(samples > 3000);
  const double theta = sum / samples;
  INFO("mean contact normal at " << theta * 180 / std::numbers::pi << " degrees over " << samples
                                 << " samples; atan(mu) " << std::atan(mu) * 180 / std::numbers::pi);
  CHECK(std::abs(theta - std::atan(mu)) < std::numbers::pi / 180);
  // Against the still drum the box stays at the bottom.
  gf::DemSimulation still = gf::DemSimulation::from_text(scene(0.0, mu, 1.0));
  still.advance(still.scene().main_steps());
  CHECK(std::abs(still.world().tables.get<gf::Bodies>().vel.x[0]) < 1e-9);
  CHECK(std::abs(still.world().tables.get<gf::Bodies>().omega.z[0]) < 1e-9);
}

TEST_CASE("walls bodies cannot meet are refused with the key and the fix") {
  const std::string base = scene(0.0, 0.5, 0.1);
  std::string turning = base + "\n[[wall]]\ntype = \"plane\"\npoint = [0.0, -0.06, 0.0]\nnormal = [0.0, 1.0, 0.0]\n"
                               "omega = 1.0\nrotation_axis = [0.0, 0.0, 1.0]\n";
  CHECK_THAT(load_error(turning), Catch::Contains("rotation_axis") && Catch::Contains("turn the plane about its normal"));
  std::string mesh = base + "\n[[wall]]\ntype = \"mesh\"\nfile = \"x.stl\"\n";
  CHECK_THAT(load_error(mesh), Catch::Contains("type") && Catch::Contains("mesh"));
}
