// Composite grains from a scene file: a box body dropped on a plane wall, or on a fixed box body,
// comes to rest at its half-height less the spring's static overlap, stepped by the DEM step the
// scene builds; bodies held by a fixed gate fall when its remove_at time comes and its springs go
// with it; malformed [[shape]] and [[bodies]] tables, body outputs and scenes mixing bodies with what
// they cannot meet yet are refused naming the key.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/run_loop.hpp"
#include "engine/scene.hpp"
#include "systems/bodies/bodies.hpp"
#include "systems/bodies/body_contact.hpp"
#include "systems/bodies/body_shapes.hpp"
#include "systems/setup/body_fields.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace {

// A 20 mm box (rounded by 2 mm) of 2500 kg/m^3 released 30 mm above a floor at y = 0.
const std::string kScene = R"(
[run]
dt = 1.0e-5
duration = 0.4
skin = 1.0e-3
gravity = [0.0, -9.81, 0.0]

[contact]
model = "linear_spring_dashpot"
kn = 1.0e4
kt = 6.0e3
kr = 1.0e-3
en = 0.3
et = 0.3
er = 0.3
friction = 0.5
rolling_friction = 0.0

[[wall]]
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 1.0, 0.0]

[[shape]]
name = "cube"
kind = "box"
size = [0.02, 0.02, 0.02]
radius = 0.002
density = 2500.0
grid = 5.0e-4

[[bodies]]
shape = "cube"
positions = [[0.0, 0.04, 0.0]]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string load_error(const std::string& text) {
  return gf::test::scene_error_of([&] { gf::DemSimulation::from_text(text); });
}

}  // namespace

TEST_CASE("a box body dropped on a plane wall rests at its half-height less m g / kn") {
  gf::DemSimulation sim = gf::DemSimulation::from_text(kScene);
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 1);
  // One member, one plane contact: the static overlap is m g / kn with the body's voxel mass.
  const double expected = 0.01 - b.mass.m[0] * 9.81 / 1.0e4;
  INFO("y = " << b.pos.y[0] << " m, expected " << expected << " m, off by " << b.pos.y[0] - expected << " m");
  CHECK(std::abs(b.pos.y[0] - expected) < 1.0e-7);
  CHECK(std::abs(b.vel.y[0]) < 1.0e-4);
  CHECK(std::abs(b.pos.x[0]) < 1.0e-9);
  // A face lands flat: no spin left (the cube's principal axes, and so q, are arbitrary).
  CHECK(std::hypot(b.omega.x[0], b.omega.y[0], b.omega.z[0]) < 1.0e-6);
}

TEST_CASE("malformed shape and bodies keys are refused naming the key") {
  CHECK_THAT(load_error(replaced(kScene, "kind = \"box\"", "kind = \"ball\"")), Catch::Contains("shape[0].kind"));
  CHECK_THAT(load_error(replaced(kScene, "size = [0.02, 0.02, 0.02]", "size = [0.02, 0.02]")),
             Catch::Contains("shape[0].size"));
  CHECK_THAT(load_error(replaced(kScene, "radius = 0.002", "radius = 0.02")), Catch::Contains("shape[0].kind"));
  CHECK_THAT(load_error(replaced(kScene, "shape = \"cube\"", "shape = \"cubes\"")), Catch::Contains("bodies[0].shape"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, 0.04]]")),
             Catch::Contains("bodies[0].positions"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, -0.04, 0.0]]")),
             Catch::Contains("behind wall"));
  CHECK_THAT(load_error(kScene + "\n[[fill]]\nkind = \"random\"\n"), Catch::Contains("fill"));
  CHECK_THAT(load_error(replaced(kScene, "type = \"plane\"", "type = \"mesh\"")), Catch::Contains("wall[0].type"));
}

TEST_CASE("bodies placed by count in a region keep their bounding spheres apart") {
  const std::string text = replaced(kScene, "positions = [[0.0, 0.04, 0.0]]",
                                    "count = 6\norientation = \"random\"\n"
                                    "region = { shape = \"box\", lo = [-0.05, 0.02, -0.05], hi = [0.05, 0.1, 0.05] }");
  gf::DemSimulation sim = gf::DemSimulation::from_text(text);
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 6);
  const double bound = std::sqrt(3.0) * 0.008 + 0.002;  // the core's corner distance + r
  for (std::size_t i = 0; i < b.n; ++i)
    for (std::size_t j = i + 1; j < b.n; ++j)
      CHECK(std::hypot(b.pos.x[i] - b.pos.x[j], b.pos.y[i] - b.pos.y[j], b.pos.z[i] - b.pos.z[j]) >= 2 * bound);
  sim.advance(100);
}

TEST_CASE("a box resting on a fixed box rests at the fixed box's top plus its half-height less m g / kn") {
  // The floor is a fixed 100 x 20 x 100 mm slab centred at y = 0 (top face at 10 mm): a wall for the
  // law (m* = the cube's mass), so the static overlap is m g / kn as on a plane.
  const std::string text = replaced(kScene, "[[bodies]]\nshape = \"cube\"\npositions = [[0.0, 0.04, 0.0]]",
                                    "[[shape]]\nname = \"slab\"\nkind = \"box\"\nsize = [0.1, 0.02, 0.1]\n"
                                    "radius = 0.002\ndensity = 2500.0\ngrid = 2.0e-3\n\n"
                                    "[[bodies]]\nshape = \"slab\"\nfixed = true\npositions = [[0.0, -0.05, 0.0]]\n\n"
                                    "[[bodies]]\nshape = \"cube\"\npositions = [[0.01, -0.01, 0.0]]");
  gf::DemSimulation sim = gf::DemSimulation::from_text(replaced(text, "point = [0.0, 0.0, 0.0]", "point = [0.0, -1.0, 0.0]"));
  sim.advance(sim.scene().main_steps());
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 2);
  const double expected = -0.05 + 0.01 + 0.01 - b.mass.m[1] * 9.81 / 1.0e4;
  INFO("y = " << b.pos.y[1] << " m, expected " << expected << " m, off by " << b.pos.y[1] - expected << " m");
  // Unlike a plane (which pushes at the mean of the vertices through it), a member pair touches at
  // the one point GJK gives on the two faces, so the cube rocks about it at the step's scale: it
  // rests within 1 % of the static overlap (1.9e-5 m) and creeps less than 0.1 mm sideways.
  CHECK(std::abs(b.pos.y[1] - expected) < 2.0e-7);
  CHECK(std::abs(b.vel.y[1]) < 1.0e-4);
  CHECK(std::abs(b.pos.x[1] - 0.01) < 1.0e-4);
  // The slab felt the cube's weight and stayed exactly where it was.
  CHECK(b.pos.x[0] == 0.0);
  CHECK(b.pos.y[0] == -0.05);
  CHECK(b.vel.x[0] == 0.0);
  CHECK(b.vel.y[0] == 0.0);
  CHECK(b.motion.state[0] == static_cast<std::uint8_t>(gf::Motion::fixed));
  CHECK(sim.world().resources.get<gf::BodyContactState>().last.fixed_contacts == 1);
}

TEST_CASE("bodies above a gate fall once it is removed, and its springs are dropped") {
  // A fixed 60 mm slab (the gate) at y = 0.1 m holds two cubes until t = 0.15 s of the main stage
  // (after 0.05 s of settling, when it must not be removed); then they fall onto the floor at y = 0.
  std::string text = replaced(kScene, "[[bodies]]\nshape = \"cube\"\npositions = [[0.0, 0.04, 0.0]]",
                              "[[shape]]\nname = \"gate\"\nkind = \"box\"\nsize = [0.06, 0.01, 0.06]\n"
                              "radius = 0.002\ndensity = 2500.0\ngrid = 1.0e-3\n\n"
                              "[[bodies]]\nshape = \"gate\"\nfixed = true\nremove_at = 0.15\n"
                              "positions = [[0.0, 0.1, 0.0]]\n\n"
                              "[[bodies]]\nshape = \"cube\"\npositions = [[-0.012, 0.12, 0.0], [0.012, 0.12, 0.0]]");
  text = replaced(text, "duration = 0.4", "duration = 0.6");
  gf::DemSimulation sim = gf::DemSimulation::from_text(text + "\n[settle]\ntime = 0.05\n");
  sim.settle();
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  const double on_gate = 0.1 + 0.005 + 0.01 - b.mass.m[1] * 9.81 / 1.0e4;
  REQUIRE(b.motion.state[0] == static_cast<std::uint8_t>(gf::Motion::fixed));
  sim.advance(14999);  // to t = 0.14999 s
  for (std::size_t i : {1, 2}) {
    INFO("body " << i << " at y = " << b.pos.y[i] << " m; resting on the gate at " << on_gate << " m");
    CHECK(std::abs(b.pos.y[i] - on_gate) < 1.0e-5);
  }
  const gf::BodyContactState& st = sim.world().resources.get<gf::BodyContactState>();
  CHECK(st.last.fixed_contacts == 2);
  CHECK(st.history.size() == 2);  // the two cubes' springs on the gate
  sim.advance(2);
  CHECK(b.motion.state[0] == static_cast<std::uint8_t>(gf::Motion::removed));
  CHECK(st.history.size() == 0);  // the gate's springs dropped with it
  CHECK(st.list.pairs() <= 1);    // only the two cubes can still be listed together
  sim.advance(sim.scene().main_steps() - 15001);
  for (std::size_t i : {1, 2}) {
    const double on_floor = 0.01 - b.mass.m[i] * 9.81 / 1.0e4;
    INFO("body " << i << " at y = " << b.pos.y[i] << " m, v_y = " << b.vel.y[i] << " m/s; resting on the floor at "
                 << on_floor << " m");
    // On the floor, 0.1 m below the gate, still rocking a little after the landing (not at rest to
    // the static overlap as on the gate, 0.3 s after it was put there).
    CHECK(std::abs(b.pos.y[i] - on_floor) < 1.0e-4);
    CHECK(std::abs(b.vel.y[i]) < 1.0e-2);
  }
  // The removed gate stays inert where it was.
  CHECK(b.pos.y[0] == 0.1);
  CHECK(b.vel.y[0] == 0.0);
}

TEST_CASE("bodies scene keys for fixed bodies, outputs and analysis are checked naming the key") {
  const std::string fixed = replaced(kScene, "shape = \"cube\"\npositions", "shape = \"cube\"\nfixed = true\npositions");
  CHECK_THAT(load_error(fixed), Catch::Contains("bodies[0].fixed") && Catch::Contains("nothing would move"));
  CHECK_THAT(load_error(replaced(fixed, "fixed = true", "fixed = true\nvelocity = [0, 1, 0]")),
             Catch::Contains("bodies[0].velocity"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, 0.04, 0.0]]\nremove_at = -1")),
             Catch::Contains("bodies[0].remove_at"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]", "positions = [[0.0, 0.04, 0.0]]\ngroup = -2")),
             Catch::Contains("bodies[0].group"));
  CHECK_THAT(load_error(kScene + "\n[output]\npicture_interval = 1.0e-6\n"), Catch::Contains("output.picture_interval"));
  CHECK_THAT(load_error(replaced(kScene, "positions = [[0.0, 0.04, 0.0]]",
                                 "count = 100\narrangement = \"lattice\"\n"
                                 "region = { shape = \"box\", lo = [-0.05, 0.02, -0.05], hi = [0.05, 0.1, 0.05] }")),
             Catch::Contains("bodies[0].count") && Catch::Contains("lattice") && Catch::Contains("hi[1]"));
  CHECK_THAT(load_error(kScene + "\n[output]\npicture_angles = [1.0]\n"), Catch::Contains("output.picture_angles"));
  CHECK_THAT(load_error(kScene + "\n[output]\npicture_colour = \"speed\"\n"), Catch::Contains("output.picture_colour"));
  CHECK_THAT(load_error(kScene + "\n[output]\nframe_force = true\n"), Catch::Contains("output.frame_force"));
  CHECK_THAT(load_error(kScene + "\n[analysis]\nmixing_cell = 0.01\n"), Catch::Contains("analysis.mixing_cell"));
  CHECK_THAT(load_error(kScene + "\n[analysis]\noutlet_heigth = 0.01\n"), Catch::Contains("outlet_heigth"));
  CHECK_THAT(load_error(kScene + "\n[analysis]\noutlet_height = 0.01\n[sink]\nheight = 0.02\n"),
             Catch::Contains("sink.height"));
  CHECK_THAT(load_error(kScene + "\n[periodic]\nx = [-1, 1]\n"), Catch::Contains("periodic"));
  CHECK_THAT(load_error(kScene + "\n[[species]]\nname = \"a\"\ndiameter = 0.01\ndensity = 1000\n[[outlet]]\n"),
             Catch::Contains("outlet") && Catch::Contains("[[fill]]"));
}

TEST_CASE("the [[shape]] key table states a letter's default sizes") {
  const gf::LetterSize size;  // what build_letter starts from
  CHECK(gf::kShapeFields.field("width").fallback == size.width);
  CHECK(gf::kShapeFields.field("depth").fallback == size.depth);
  CHECK(gf::kShapeFields.field("stroke").fallback == size.stroke);
  CHECK(size.height == 0.180);  // the table's words: "0.180 (`letter`)"
  CHECK_THAT(std::string(gf::kShapeFields.field("height").default_text), Catch::Contains("0.180 (`letter`)"));
}

TEST_CASE("a body contact overlapping past run.max_overlap stops the run naming the limit and the fix") {
  // The cube lands at 0.63 m/s on a 1e4 N/m spring: its largest overlap is v sqrt(m / kn) = 0.9 mm,
  // 4 % of its 20 mm side. A limit of 1 % (0.2 mm) is passed at the landing; the default 10 % is not.
  gf::DemSimulation stops = gf::DemSimulation::from_text(kScene, {"run.max_overlap=1.0e-2"});
  std::string message;
  try {
    stops.advance(stops.scene().main_steps());
  } catch (const gf::StabilityError& e) {
    message = e.what();
  }
  CHECK_THAT(message, Catch::Contains("overlaps by") && Catch::Contains("limit of 0.0002 m") &&
                          Catch::Contains("run.max_overlap"));
  // It names the contact: the one cube's one member, on the floor.
  CHECK_THAT(message, Catch::Contains("member 0 of body 0 against a wall"));
  CHECK(stops.world().clock.t < 0.1);  // at the landing, about 0.064 s after the release
  gf::DemSimulation runs = gf::DemSimulation::from_text(kScene);
  CHECK_NOTHROW(runs.advance(runs.scene().main_steps()));
}

TEST_CASE("the step check's rim mass is the effective mass at a cube's corner") {
  // A cube's inertia is isotropic, I0 about any axis, so at a corner r from the centre the largest
  // (r x n)^T I^-1 (r x n) is |r|^2 / I0 (n across r), and the corner meets 1 / (1/m + |r|^2 / I0):
  // m / 5.5 for a sharp cube. The voxel moments of the rounded cube are equal by symmetry to
  // round-off, so 1e-9 of the mass.
  gf::DemSimulation sim = gf::DemSimulation::from_text(kScene);
  const gf::BodyShape& cube = sim.scene().bodies->shapes.at(0);
  double corner = 0;
  for (const gf::DilatedPolyhedron& m : gf::shape_members(cube.shape))
    for (const Eigen::Vector3d& v : m.vertices) corner = std::max(corner, (v - cube.props.centre).norm());
  const double i0 = cube.props.moments.mean(), m = cube.props.mass;
  CHECK(cube.props.moments.maxCoeff() - cube.props.moments.minCoeff() < 1e-9 * i0);
  CHECK(gf::rim_mass(cube) == Approx(1.0 / (1.0 / m + corner * corner / i0)).epsilon(1e-9));
  // The step check's rim terms are then shorter than its own by up to sqrt(m / rim mass).
  CHECK(sim.scene().bodies->rim.period <= sim.scene().bodies->critical.period);
  CHECK(sim.scene().bodies->rim.period >= sim.scene().bodies->critical.period * std::sqrt(gf::rim_mass(cube) / m) * (1 - 1e-12));
}
