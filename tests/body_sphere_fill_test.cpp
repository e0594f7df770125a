// The grain tables' spheres among composite bodies (systems/setup/body_sphere_fill.hpp): [[species]]
// and [[fill]] place spheres that join the bodies as one-member bodies. A random fill keeps them
// clear of the bodies, of each other and of the walls, with each species' exact mass; a file fill
// gives the same bodies, to the bit through a run, as the same spheres placed by [[bodies]] tables;
// what bodies cannot honour is refused naming the key.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "systems/bodies/bodies.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/body_test_support.hpp"
#include "tests/test_support.hpp"

namespace {

constexpr double kPi = std::numbers::pi;

std::string scene(const std::string& run, const std::string& rest) { return gf::test::body_scene(run, rest); }

// A fixed slab whose top face is at y = 0, under a box of walls.
const std::string kSlab =
    "[[shape]]\nname = \"slab\"\nkind = \"box\"\nsize = [0.1, 0.02, 0.1]\nradius = 0.002\ndensity = 2500.0\ngrid = 2.0e-3\n\n"
    "[[bodies]]\nshape = \"slab\"\nfixed = true\npositions = [[0.0, -0.01, 0.0]]\n\n"
    "[[wall]]\ntype = \"box\"\nlo = [-0.05, -0.03, -0.05]\nhi = [0.05, 0.1, 0.05]\n\n";

const std::string kSpecies =
    "[[species]]\nname = \"small\"\ndiameter = 0.004\ndensity = 2500.0\n\n"
    "[[species]]\nname = \"large\"\ndiameter = 0.008\ndensity = 7800.0\n\n";

std::string load_error(const std::string& text) {
  return gf::test::scene_error_of([&] { gf::DemSimulation::from_text(text); });
}

double sphere_mass(double d, double rho) { return rho * 4.0 / 3.0 * kPi * d * d * d / 8.0; }

}  // namespace

TEST_CASE("a random fill among bodies places spheres clear of the bodies, each other and the walls") {
  const std::string fill =
      "[[fill]]\nkind = \"random\"\nseed = 3\nregion = { shape = \"box\", lo = [-0.05, -0.03, -0.05], hi = [0.05, 0.1, 0.05] }\n"
      "count = { small = 60, large = 20 }\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene("duration = 0.0\n", kSlab + kSpecies + fill));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 81);
  REQUIRE(sim.world().tables.get<gf::Members>().n == 81 + 0);  // the slab is one member, each sphere one
  const auto& shapes = sim.scene().bodies->shapes;
  REQUIRE(shapes.size() == 3);
  int small = 0, large = 0;
  for (std::size_t i = 1; i < b.n; ++i) {
    const gf::BodyPlacement& p = sim.scene().bodies->placed[i];
    const bool is_small = shapes[p.shape].name == "small";
    (is_small ? small : large) += 1;
    const double r = is_small ? 0.002 : 0.004;
    CHECK(b.mass.m[i] == Approx(sphere_mass(2 * r, is_small ? 2500.0 : 7800.0)).epsilon(1e-14));
    CHECK(p.group == 1);  // after the one [[bodies]] table
    // Clear of the slab's bounding sphere and of the walls (inside the box by at least r).
    const double to_slab = std::hypot(b.pos.x[i] - 0.0, b.pos.y[i] + 0.01, b.pos.z[i] - 0.0);
    CHECK(to_slab >= r + shapes[0].bound);
    for (const double x : {b.pos.x[i], b.pos.z[i]}) CHECK(std::abs(x) <= 0.05 - r);
    CHECK(b.pos.y[i] <= 0.1 - r);
    for (std::size_t j = i + 1; j < b.n; ++j) {
      const double rj = shapes[sim.scene().bodies->placed[j].shape].bound;
      CHECK(std::hypot(b.pos.x[i] - b.pos.x[j], b.pos.y[i] - b.pos.y[j], b.pos.z[i] - b.pos.z[j]) >= r + rj);
    }
  }
  CHECK(small == 60);
  CHECK(large == 20);
}

TEST_CASE("two random fills among bodies keep clear of each other as well as of the bodies") {
  const std::string fills =
      "[[fill]]\nkind = \"random\"\nseed = 3\nregion = { shape = \"box\", lo = [-0.05, -0.03, -0.05], hi = [0.05, 0.1, 0.05] }\n"
      "count = { large = 40 }\n\n"
      "[[fill]]\nkind = \"random\"\nseed = 3\nregion = { shape = \"box\", lo = [-0.05, -0.03, -0.05], hi = [0.05, 0.1, 0.05] }\n"
      "count = { small = 100 }\n";
  gf::DemSimulation sim = gf::DemSimulation::from_text(scene("duration = 0.0\n", kSlab + kSpecies + fills));
  const gf::Bodies& b = sim.world().tables.get<gf::Bodies>();
  REQUIRE(b.n == 141);
  const auto& placed = sim.scene().bodies->placed;
  const auto& shapes = sim.scene().bodies->shapes;
  CHECK(placed[1].group == 1);
  CHECK(placed[140].group == 2);
  std::size_t close = 0;
  for (std::size_t i = 0; i < b.n; ++i)
    for (std::size_t j = i + 1; j < b.n; ++j)
      close += std::hypot(b.pos.x[i] - b.pos.x[j], b.pos.y[i] - b.pos.y[j], b.pos.z[i] - b.pos.z[j]) <
               shapes[placed[i].shape].bound + shapes[placed[j].shape].bound;
  CHECK(close == 0);
}

TEST_CASE("a file fill among bodies runs bit for bit as the same spheres placed by [[bodies]]") {
  gf::test::TempDir dir("body_sphere_fill");
  dir.write("state.csv",
            "id,type,diameter,x,y,z,vx,vy,vz,wx,wy,wz\n"
            "7,1,0.004,0.001,0.01,0.0,0.1,-0.2,0.0,0.0,0.0,3.0\n"
            "8,2,0.008,-0.02,0.02,0.01,0.0,0.0,0.05,1.0,0.0,0.0\n"
            "9,1,0.004,0.02,0.004,-0.01,0.0,0.0,0.0,0.0,0.0,0.0\n");
  const std::string run = "duration = 0.05\ngravity = [0.0, -9.81, 0.0]\n";
  const std::string by_fill = kSlab + kSpecies + "[[fill]]\nkind = \"file\"\npath = \"" + (dir.path / "state.csv").string() +
                              "\"\ntypes = { 1 = \"small\", 2 = \"large\" }\n";
  // The same spheres as shapes of the species' names, density and radius, one [[bodies]] table each.
  const std::string shapes = "[[shape]]\nname = \"small\"\nkind = \"sphere\"\nradius = 0.002\ndensity = 2500.0\n\n"
                             "[[shape]]\nname = \"large\"\nkind = \"sphere\"\nradius = 0.004\ndensity = 7800.0\n\n";
  auto one = [](const char* shape, const char* x, const char* v) {
    return std::string("[[bodies]]\nshape = \"") + shape + "\"\npositions = [" + x + "]\nvelocity = " + v + "\n\n";
  };
  const std::string by_bodies = kSlab + shapes + one("small", "[0.001, 0.01, 0.0]", "[0.1, -0.2, 0.0]") +
                                one("large", "[-0.02, 0.02, 0.01]", "[0.0, 0.0, 0.05]") +
                                one("small", "[0.02, 0.004, -0.01]", "[0.0, 0.0, 0.0]");
  gf::DemSimulation a = gf::DemSimulation::from_text(scene(run, by_fill));
  gf::DemSimulation b = gf::DemSimulation::from_text(scene(run, by_bodies));
  // [[bodies]] give no spins: the file's are set on the second run's rows before it starts.
  gf::Bodies& rb = b.world().tables.get<gf::Bodies>();
  rb.omega.z[1] = 3.0;
  rb.omega.x[2] = 1.0;
  const gf::Bodies& ra = a.world().tables.get<gf::Bodies>();
  REQUIRE(ra.n == 4);
  REQUIRE(rb.n == 4);
  CHECK(ra.omega.z[1] == 3.0);
  CHECK(ra.vel.z[2] == 0.05);
  a.advance(a.scene().main_steps());
  b.advance(b.scene().main_steps());
  for (std::size_t i = 0; i < 4; ++i) {
    INFO("body " << i);
    CHECK(ra.pos.x[i] == rb.pos.x[i]);
    CHECK(ra.pos.y[i] == rb.pos.y[i]);
    CHECK(ra.pos.z[i] == rb.pos.z[i]);
    CHECK(ra.omega.x[i] == rb.omega.x[i]);
    CHECK(ra.omega.z[i] == rb.omega.z[i]);
  }
  CHECK(ra.pos.y[3] < 0.004);  // the third sphere fell onto the slab meanwhile
}

TEST_CASE("spheres among bodies refuse what bodies cannot honour, naming the key") {
  const std::string run = "duration = 0.0\n";
  const std::string fill = "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [-0.04, 0.01, -0.04], hi = [0.04, 0.09, 0.04] }\n"
                           "count = { small = 5 }\n";
  const std::string small = "[[species]]\nname = \"small\"\ndiameter = 0.004\ndensity = 2500.0\n";
  CHECK_THAT(load_error(scene(run, kSlab + small + "rotates = false\n\n" + fill)),
             Catch::Contains("species[0].rotates") && Catch::Contains("always rotates"));
  std::string paired = scene(run, kSlab + small + "\n" + fill);
  paired.replace(paired.find("[[shape]]"), 0, "[[contact.pair]]\nspecies_a = \"small\"\nspecies_b = \"small\"\nfriction = 0.1\n\n");
  CHECK_THAT(load_error(paired), Catch::Contains("contact.pair[0].species_a") && Catch::Contains("one set of contact"));
  std::string renamed = fill;
  renamed.replace(renamed.find("small ="), 5, "slab");
  CHECK_THAT(load_error(scene(run, kSlab + "[[species]]\nname = \"slab\"\ndiameter = 0.004\ndensity = 2500.0\n\n" + renamed)),
             Catch::Contains("species[0].name") && Catch::Contains("rename"));
  const std::string through = "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [-0.06, 0.01, -0.04], hi = [0.04, 0.09, 0.04] }\n"
                              "count = { small = 40 }\n";
  CHECK_THAT(load_error(scene(run, kSlab + small + "\n" + through)), Catch::Contains("fill[0]") && Catch::Contains("reaches through wall"));
  CHECK_THAT(load_error(scene(run, kSlab + small + "\n" + fill + "[[feed]]\nspecies = \"small\"\n")),
             Catch::Contains("feed") && Catch::Contains("[[fill]]"));
  gf::test::TempDir dir("body_sphere_fill_bad");
  dir.write("state.csv", "id,type,diameter,x,y,z\n1,3,0.004,0.0,0.01,0.0\n");
  CHECK_THAT(load_error(scene(run, kSlab + small + "\n[[fill]]\nkind = \"file\"\npath = \"" + (dir.path / "state.csv").string() +
                                          "\"\ntypes = { 1 = \"small\" }\n")),
             Catch::Contains("state.csv:2") && Catch::Contains("type 3 is not mapped"));
}

TEST_CASE("under hertz_mindlin a species among bodies must have the shapes' material") {
  auto hertz = [](const std::string& species_modulus) {
    return std::string("[run]\ndt = 1.0e-6\nduration = 0.0\nskin = 1.0e-3\n\n"
                       "[contact]\nmodel = \"hertz_mindlin\"\nrestitution = 0.5\nfriction = 0.5\nrolling_friction = 0.0\n\n") +
           "[[shape]]\nname = \"slab\"\nkind = \"box\"\nsize = [0.1, 0.02, 0.1]\nradius = 0.002\ndensity = 2500.0\ngrid = 2.0e-3\n"
           "youngs_modulus = 1.0e7\npoisson_ratio = 0.25\n\n"
           "[[bodies]]\nshape = \"slab\"\nfixed = true\npositions = [[0.0, -0.01, 0.0]]\n\n"
           "[[species]]\nname = \"small\"\ndiameter = 0.004\ndensity = 2500.0\nyoungs_modulus = " + species_modulus +
           "\npoisson_ratio = 0.25\n\n"
           "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [-0.04, 0.01, -0.04], hi = [0.04, 0.09, 0.04] }\n"
           "count = { small = 5 }\n";
  };
  CHECK_NOTHROW(gf::DemSimulation::from_text(hertz("1.0e7")));
  CHECK_THAT(load_error(hertz("2.0e7")), Catch::Contains("species[0].youngs_modulus") && Catch::Contains("one material"));
}
