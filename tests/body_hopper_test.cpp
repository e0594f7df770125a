// The seed-002 flat-bottomed hopper of triangular prisms (scenes/hopper_seed002_prisms.toml),
// reduced to 100 prisms and a short time, run through the command line: the pour settles on the
// closed gate, the gate opens at t = 0 of the main stage, and the remaining fraction above the
// bottom falls while the prisms that pass the outlet reach the sink; overlaps stay small.
#include <catch2/catch.hpp>

#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.hpp"

namespace {

std::vector<double> numbers(const std::string& line) {
  std::vector<double> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(std::stod(f));
  return out;
}

}  // namespace

TEST_CASE("seed 002 hopper of 100 prisms: the remaining fraction falls once the gate opens", "[bodies][cli]") {
  gf::test::TempDir dir("body_hopper");
  const std::string scene = std::string(GRAINFLOW_SOURCE_DIR) + "/scenes/hopper_seed002_prisms.toml";
  const std::filesystem::path out = dir.path / "out";
  const gf::test::Exit e = gf::test::run_cli(
      dir, "run " + gf::test::quote(scene) + " --quiet --out " + gf::test::quote(out.string()) +
               " --set bodies.2.count=100 --set settle.time=0.3 --set run.duration=0.3"
               " --set output.frame_interval=0 --set output.picture_interval=0.3");
  INFO(e.err);
  REQUIRE(e.code == 0);
  const std::vector<std::string> rows = gf::test::read_lines(out / "series.csv");
  REQUIRE(rows.size() == 32);  // header, t = 0 .. 0.3 s every 0.01 s
  REQUIRE(rows[0] == "time,ke_translational,ke_rotational,contacts,wall_contacts,max_overlap_ratio,moving,"
                     "remaining_fraction");
  const std::vector<double> first = numbers(rows[1]), last = numbers(rows.back());
  // Settled on the closed gate: all 100 above the bottom, nearly at rest (kinetic energy below
  // that of one prism, 6.1e-4 kg, moving at 5 cm/s).
  CHECK(first[6] == 100);
  CHECK(first[7] == 1.0);
  CHECK(first[1] < 0.5 * 6.1e-4 * 0.05 * 0.05);
  // The prisms over the 40 mm outlet leave; those on the two 50 mm floors stay (a layer about 1.5
  // prisms deep has no head to push them off): between a tenth and two thirds of them go.
  INFO("remaining fraction at 0.3 s: " << last[7]);
  CHECK(last[7] < 0.9);
  CHECK(last[7] > 0.33);
  CHECK(last[6] < 100);                     // the sink took those that fell through
  CHECK(last[6] >= last[7] * 100 - 1e-9);  // moving: those above the outlet and any still falling
  double previous = 1.0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::vector<double> r = numbers(rows[k]);
    CHECK(r[7] <= previous);
    previous = r[7];
    CHECK(r[5] < 0.01);  // overlaps below 1 % of the prism's smallest dimension
  }
  CHECK(gf::test::read_file(out / "pictures" / "time_0000.3000.png").size() > 100);
}
