// The input fuzzer's fixed-seed slice: 1,000 mutated scenes, --set arguments, state CSVs and
// checkpoints (tests/input_fuzz.hpp says what is mutated and what each input must satisfy). The
// bases are the small scenes of every kind (grains, composite grains, a mixer, liquid, liquid with grains), so the
// slice stays within seconds, under the sanitizers too; the validation run
// (tests/validation/input_fuzz_validation_test.cpp) takes every scene of scenes/.
#include <catch2/catch.hpp>

#include "tests/input_fuzz.hpp"

TEST_CASE("1,000 mutated inputs: no crash, bounded time and memory, every refusal located with a fix",
          "[fuzz]") {
  gf::fuzz::Settings s;
  s.seed = 20261123;
  s.inputs = 1000;
  s.scenes = {"tests/sphere_on_plane.toml", "tests/two_sphere_collision.toml", "tests/sphere_in_drum.toml",
              "tests/elastic_box.toml",     "drum_quick.toml",                 "bench/settled_layer.toml",
              "liquid/hydrostatic_2d.toml", "liquid/dam_break_2d.toml",        "liquid/poiseuille_2d.toml",
              "mixer_seed004_design1.toml", "liquid/settling_grain.toml", "hopper_ellipsoids.toml",
              "liquid/packed_bed.toml"};
  s.checkpoints = {"tests/sphere_in_drum.toml"};
  gf::fuzz::Fuzzer f(s);
  const gf::fuzz::Report r = f.run();
  INFO(gf::fuzz::dump(r.json(s)));
  for (const std::string& d : r.defects) UNSCOPED_INFO(d);
  CHECK(r.defects.empty());
  WARN(gf::fuzz::dump(r.json(s)));
  // Every target was reached, and both sides of each: refused and accepted inputs.
  for (const char* t : {"scene", "override", "state_csv", "checkpoint"}) {
    CHECK(r.refused.count(t) == 1);
    CHECK(r.accepted.count(t) == 1);
  }
  CHECK(r.runs > 50);
}
