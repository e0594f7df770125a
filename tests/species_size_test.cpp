// A species' diameter as a size distribution in a scene (systems/setup/species_size.hpp): the keys read,
// a fill's grains drawn from the law with their own masses and inertias, a volume fraction counted at the
// law's mean volume, a size table from a file, a state file's diameters checked against the law's range,
// the critical step of the smallest grains, and the mistakes named at their keys.
#include "systems/setup/dem_simulation.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "engine/scene.hpp"
#include "tests/test_support.hpp"

using gf::DemSimulation;
using gf::test::scene_error_of;

namespace {

// 1500 glass grains poured into a 30 mm box under seed 000's linear law, their diameter given by `diameter`; the
// step is within the limit of 1 mm grains.
std::string box_scene(const std::string& diameter, const std::string& fill = "count = { glass = 1500 }") {
  return "[run]\ndt = 5.0e-6\nduration = 0.001\nskin = 1.5e-4\n"
         "[[species]]\nname = \"glass\"\ndiameter = " + diameter + "\ndensity = 2500.0\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
         "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
         "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.03, 0.03]\n"
         "[[fill]]\nkind = \"random\"\nregion = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.03, 0.03, 0.03] }\n" +
         fill + "\n";
}

const std::string kNormal = "{ distribution = \"normal\", mean = 2.0e-3, sd = 2.0e-4 }";

}  // namespace

TEST_CASE("a fill draws each grain's diameter from a normal law, with the grain's own mass and inertia") {
  DemSimulation sim = DemSimulation::from_text(box_scene(kNormal));
  const gf::Grains& g = sim.grains();
  REQUIRE(g.n_owned == 1500);
  const gf::SizeDistribution& law = sim.scene().species[0].size;
  CHECK(law.smallest() == Approx(1.4e-3));
  CHECK(law.largest() == Approx(2.6e-3));
  double mean = 0.0;
  for (std::size_t i = 0; i < g.n_owned; ++i) {
    const double d = 2.0 * g.radius.r[i];
    CHECK(d >= law.smallest());
    CHECK(d <= law.largest());
    const double m = 2500.0 * std::numbers::pi / 6.0 * d * d * d;
    CHECK(g.mass.m[i] == Approx(m).epsilon(1e-14));
    CHECK(g.mass.inv_inertia[i] == Approx(1.0 / (0.1 * m * d * d)).epsilon(1e-14));
    mean += d / 1500.0;
  }
  // Within five standard errors of the law's mean (sd/sqrt(1500) = 5.2e-6 m).
  const double se = std::sqrt(law.moment(2) - law.moment(1) * law.moment(1)) / std::sqrt(1500.0);
  CHECK(std::abs(mean - law.moment(1)) < 5.0 * se);
  // The critical step is the smallest grains': that of a fixed species of 1.4 mm.
  DemSimulation fixed = DemSimulation::from_text(box_scene("1.4e-3"));
  CHECK(sim.scene().critical.period == Approx(fixed.scene().critical.period).epsilon(1e-12));
  CHECK(sim.scene().contacts->sized());
  CHECK_FALSE(fixed.scene().contacts->sized());
}

TEST_CASE("a size distribution given on the command line, and a volume fraction counted at the law's mean volume") {
  DemSimulation sim = DemSimulation::from_text(
      box_scene("2.0e-3", "volume_fraction = { glass = 0.2 }"),
      {"species.0.diameter={ distribution = \"lognormal\", mean = 1.5e-3, sd = 3.0e-4 }"});
  const gf::SizeDistribution& law = sim.scene().species[0].size;
  CHECK(law.kind == gf::SizeDistribution::Kind::LogNormal);
  const double n = 0.2 * 0.03 * 0.03 * 0.03 / (std::numbers::pi / 6.0 * law.moment(3));
  CHECK(static_cast<double>(sim.grains().n_owned) == Approx(std::round(n)).margin(1.0));
}

TEST_CASE("a size table from a file, by mass, and a state file's diameters against the law's range") {
  const gf::test::TempDir dir("species_size");
  std::ofstream(dir.path / "sieve.csv") << "# sieve analysis\ndiameter,fraction\n1.0e-3, 50\n2.0e-3, 50\n";
  const std::string by_file = "{ distribution = \"file\", file = \"sieve.csv\", by = \"mass\" }";
  std::ofstream(dir.path / "scene.toml") << box_scene(by_file, "count = { glass = 900 }");
  DemSimulation sim = DemSimulation::from_file(dir.path / "scene.toml");
  // Equal masses of 1 and 2 mm grains: eight small grains to one large by number.
  std::size_t large = 0;
  for (std::size_t i = 0; i < sim.grains().n_owned; ++i) large += sim.grains().radius.r[i] > 0.75e-3;
  CHECK(std::abs(large / 900.0 - 1.0 / 9.0) < 5.0 * std::sqrt(1.0 / 9.0 * 8.0 / 9.0 / 900.0));

  std::ofstream(dir.path / "state.csv") << "id,type,diameter,x,y,z\n4,1,1.0e-3,0.01,0.01,0.01\n9,1,2.0e-3,0.02,0.02,0.02\n";
  const std::string from_state = "[[fill]]\nkind = \"file\"\npath = \"state.csv\"\ntypes = { 1 = \"glass\" }\n";
  std::string text = box_scene(by_file, "count = { glass = 0 }") + from_state;
  std::ofstream(dir.path / "state_scene.toml") << text;
  DemSimulation st = DemSimulation::from_file(dir.path / "state_scene.toml");
  REQUIRE(st.grains().n_owned == 2);
  CHECK(st.grains().radius.r[1] == 1.0e-3);
  CHECK(st.grains().mass.m[1] == Approx(2500.0 * std::numbers::pi / 6.0 * 8e-9));
  std::ofstream(dir.path / "state.csv") << "id,type,diameter,x,y,z\n4,1,1.0e-3,0.01,0.01,0.01\n9,1,2.5e-3,0.02,0.02,0.02\n";
  const std::string msg = scene_error_of([&] { DemSimulation::from_file(dir.path / "state_scene.toml"); });
  CHECK(msg.find("state.csv:3") != std::string::npos);
  CHECK(msg.find("0.001 to 0.002") != std::string::npos);
}

TEST_CASE("size distributions that are mistakes are named at their keys") {
  auto error = [](const std::string& diameter) { return scene_error_of([&] { DemSimulation::from_text(box_scene(diameter)); }); };
  // Diameters typed in millimetres: the largest grain is wider than the fill's region.
  std::string msg = error("{ distribution = \"discrete\", diameters = [1.0, 2.0], fractions = [1, 1] }");
  CHECK(msg.find("species[0].diameter") != std::string::npos);
  CHECK(msg.find("millimetres") != std::string::npos);
  msg = error("{ distribution = \"discrete\", diameters = [1.0e-3, 200.0], fractions = [1, 1] }");
  CHECK(msg.find("species[0].diameter.diameters") != std::string::npos);
  CHECK(msg.find("0.2 m") != std::string::npos);
  // A standard deviation so wide that mean - 3 sd is no diameter.
  msg = error("{ distribution = \"normal\", mean = 2.0e-3, sd = 1.0e-3 }");
  CHECK(msg.find("species[0].diameter.sd") != std::string::npos);
  CHECK(msg.find("give min") != std::string::npos);
  CHECK(scene_error_of([&] {
          DemSimulation::from_text(box_scene("{ distribution = \"normal\", mean = 2.0e-3, sd = 1.0e-3, min = 1.0e-3 }",
                                             "count = { glass = 200 }"));
        }).empty());
  msg = error("{ distribution = \"discrete\", diameters = [1.0e-3, 2.0e-3], fractions = [1] }");
  CHECK(msg.find("1 fractions for 2 diameters") != std::string::npos);
  msg = error("{ distribution = \"gaussian\", mean = 2.0e-3, sd = 1.0e-4 }");
  CHECK(msg.find("species[0].diameter.distribution") != std::string::npos);
  msg = error("{ distribution = \"normal\", mean = 2.0e-3, sd = 1.0e-4, by = \"mass\" }");
  CHECK(msg.find("species[0].diameter.by") != std::string::npos);
  msg = error("{ distribution = \"file\", file = \"no_such_table.csv\" }");
  CHECK(msg.find("species[0].diameter.file") != std::string::npos);
  // A grain of the law wider than the fill's region: the largest size is named.
  msg = scene_error_of([&] {
    DemSimulation::from_text(box_scene("{ distribution = \"discrete\", diameters = [1.0e-3, 40.0e-3], fractions = [1, 1] }"));
  });
  CHECK(msg.find("grains of diameter 0.04") != std::string::npos);
}

TEST_CASE("the representative-volume law keeps one size per species") {
  const std::string box = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/tests/representative_volume_box.toml";
  const std::string msg = scene_error_of([&] {
    DemSimulation::from_file(box, {"species.0.diameter={ distribution = \"normal\", mean = 4.0e-3, sd = 4.0e-4 }"});
  });
  CHECK(msg.find("species[0].diameter") != std::string::npos);
  CHECK(msg.find("one size per species") != std::string::npos);
}

TEST_CASE("a run of size distributions resumed from its checkpoint ends as the run that never stopped") {
  // Each grain's own diameter, mass and inertia travel in the checkpoint: the final state, the series and
  // walls.csv of two pieces are the bytes of one run.
  const gf::test::TempDir dir("species_size_resume");
  const std::string file = dir.write("scene.toml", box_scene(kNormal, "count = { glass = 400 }") +
                                                       "[output]\nseries_interval = 2.0e-4\nframe_interval = 0\n")
                               .string();
  const auto run = [&](const std::string& out, const std::string& more) {
    const gf::test::Exit e = gf::test::run_cli(dir, "run " + gf::test::quote(file) + " --out " +
                                                        gf::test::quote((dir.path / out).string()) +
                                                        " --threads 1 --quiet --set run.duration=0.002 " + more);
    INFO(e.err);
    REQUIRE(e.code == 0);
  };
  run("whole", "");
  run("pieces", "--steps 200");
  run("pieces", "--resume " + gf::test::quote((dir.path / "pieces" / "checkpoints" / "checkpoint.gfc").string()));
  for (const char* f : {"final_state.csv", "series.csv", "walls.csv"}) {
    CAPTURE(f);
    const std::string whole = gf::test::read_file(dir.path / "whole" / f);
    REQUIRE(!whole.empty());
    CHECK(gf::test::read_file(dir.path / "pieces" / f) == whole);
  }
}
