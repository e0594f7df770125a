// The fluidised bed's packed branch (scenes/liquid/fluidised_bed.toml, seed 003's ladder): 8000 glass beads
// of 2 mm, settled in still liquid to a bed 71 mm deep of liquid fraction 0.48, with liquid driven up
// through them below minimum fluidisation (drive 8 mm/s, a superficial speed of ~4.5 mm/s against
// Ergun's 8.1 mm/s at minimum fluidisation). Over 0.1 to 0.3 s:
//  - the bed stays put: the beads' mean speed below 0.1 mm/s;
//  - the drag carries less than 70 % of the bed's weight less buoyancy (Ergun: 58 %);
//  - the drag is Ergun's over the bed within 20 %, from below. The sweep (studies/seed003/results/fluidised_bed.csv,
//    1.5 s runs) reads 0.82 to 0.88 of Ergun (0.86 at this drive): beads within the smoothing radius (12.5 mm) of the floor
//    and the bed's top share volume with clear liquid, so the liquid fraction read at the beads is 0.50
//    against the bed's 0.48, and Ergun's (1 - eps)^2 / eps^3 is a fifth smaller at 0.50.
// The fluidised branch (1.5 s runs) is tests/validation/coupled_fluidisation_validation_test.cpp.
#include <catch2/catch.hpp>

#include "tests/fluidised_bed_support.hpp"

TEST_CASE("coupled: a packed bed below minimum fluidisation stays put and takes Ergun's drag", "[coupled][fluidised_bed]") {
  const gf::test::FluidisedBed b = gf::test::run_bed(0.008, 0.3, 0.2);
  const double ergun = b.ergun(8000);
  INFO("height " << b.height << " m, eps bed " << b.eps_bed << ", middle " << b.eps_mid << ", read at the beads "
                 << b.eps_read << "; u " << b.u << " m/s; drag / weight " << b.drag << ", Ergun " << ergun
                 << "; beads' speed " << b.speed << " m/s");
  CHECK(std::abs(b.speed) < 1e-4);
  CHECK(b.height == Approx(0.0715).margin(0.002));  // the settled bed's 71.5 mm
  CHECK(b.drag < 0.7);
  CHECK(b.drag / ergun > 0.8);
  CHECK(b.drag / ergun < 1.0);
  CHECK(b.eps_read > b.eps_bed);  // the kernel's reach past the bed's ends, which the 20 % allows for
}
