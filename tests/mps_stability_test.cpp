// Stability limits of the liquid (systems/mps/stability.hpp and the checks at scene load): every detector fires
// on a state that breaks its limit and says which limit and what to change; a real blow-up through the command
// line exits with code 3 and a "failed" summary; bad scene input is a SceneError naming file, line, key and fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>

#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "engine/scene.hpp"
#include "mps_support.hpp"
#include "systems/mps/liquid_simulation.hpp"
#include "systems/mps/stability.hpp"
#include "test_support.hpp"

using namespace gf;
namespace fs = std::filesystem;

namespace {

// A 10 x 10 block of fluid nodes at rest, n = n0, in a 2D setting with l0 = 0.01 m.
struct Block {
  FluidNodes f;
  LiquidParams lp;
  StabilityLimits lim;
  LiquidDiagnostics d;
  Block() {
    lp.k = lattice_constants(2, 0.01, 0.021);
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) f.push(kFluid, (i + 0.5) * 0.01, (j + 0.5) * 0.01, 0.0);
    for (std::size_t i = 0; i < f.size(); ++i) f.n[i] = lp.k.n0;
    lim.lo = {0, 0, 0};
    lim.hi = {0.1, 0.1, 0};
  }
};

const char* kDam = "dam_break_2d.toml";

}  // namespace

TEST_CASE("a state within every limit passes the run-time checks") {
  Block b;
  CHECK_NOTHROW(check_density(b.f, b.lp, b.lim, 0.1, b.d));
  CHECK_NOTHROW(check_motion(b.f, b.lp, b.lim, 1e-3, 0.1, b.d));
  CHECK(b.d.max_density_ratio == Approx(1.0));
  CHECK(b.d.cfl == 0.0);
}

TEST_CASE("number-density spike: n*/n0 above run.density_limit stops the run") {
  Block b;
  b.f.n[42] = 1.6 * b.lp.k.n0;  // limit 1.5
  REQUIRE_THROWS_AS(check_density(b.f, b.lp, b.lim, 0.1, b.d), LiquidFailure);
  REQUIRE_THROWS_WITH(check_density(b.f, b.lp, b.lim, 0.1, b.d),
                      Catch::Contains("number-density spike") && Catch::Contains("run.density_limit") &&
                          Catch::Contains("node 42") && Catch::Contains("Fix: reduce run.dt"));
}

TEST_CASE("CFL: max |u| dt / l0 above run.cfl_limit stops the run and names the dt that would pass") {
  Block b;
  b.f.u[7] = 6.0;  // 6 m/s * 1e-3 s / 0.01 m = 0.6 > 0.5
  REQUIRE_THROWS_WITH(check_motion(b.f, b.lp, b.lim, 1e-3, 0.1, b.d),
                      Catch::Contains("CFL limit broken") && Catch::Contains("run.cfl_limit") &&
                          Catch::Contains("reduce run.dt below 0.0008333"));
}

TEST_CASE("a particle outside the geometry's bounds, or with a non-finite state, stops the run") {
  Block b;
  b.f.x[3] = 0.5;
  REQUIRE_THROWS_WITH(check_motion(b.f, b.lp, b.lim, 1e-3, 0.1, b.d),
                      Catch::Contains("particle left the domain") && Catch::Contains("node 3"));
  Block c;
  c.f.v[5] = std::numeric_limits<double>::quiet_NaN();
  REQUIRE_THROWS_WITH(check_motion(c.f, c.lp, c.lim, 1e-3, 0.1, c.d), Catch::Contains("node 5"));
}

TEST_CASE("solver failure: a non-converged PPE stops the run with the tolerance and iteration limit") {
  PpeResult r;
  r.converged = false;
  r.iterations = 2000;
  r.residual = 3e-5;
  PpeSettings s;
  REQUIRE_THROWS_WITH(check_ppe(r, s, 0.2), Catch::Contains("pressure solver failed") &&
                                                Catch::Contains("max_iterations = 2000") && Catch::Contains("Fix:"));
}

TEST_CASE("scene load refuses a time step beyond the CFL or diffusion limit unless overridden") {
  const std::string dam = test::liquid_scene(kDam);
  // dt = 2e-3 s: CFL = sqrt(2 g 0.292) * 2e-3 / 0.0073 = 0.66 > 0.5.
  REQUIRE_THROWS_WITH(load_liquid_scene(SceneDoc::load(dam, {"run.dt=2e-3"})),
                      Catch::Contains("key 'run.dt'") && Catch::Contains("CFL number 0.65") &&
                          Catch::Contains("Fix: set dt <= 0.001") && Catch::Contains("allow_unstable_dt"));
  CHECK_NOTHROW(load_liquid_scene(SceneDoc::load(dam, {"run.dt=2e-3", "run.allow_unstable_dt=true"})));
  // nu = 1e-2 m^2/s: nu dt / l0^2 = 1e-2 * 5e-4 / 0.0073^2 = 0.094 passes; 0.05 m^2/s gives 0.47 > 0.2.
  CHECK_NOTHROW(load_liquid_scene(SceneDoc::load(dam, {"liquid.viscosity=1e-2"})));
  REQUIRE_THROWS_WITH(load_liquid_scene(SceneDoc::load(dam, {"liquid.viscosity=5e-2"})),
                      Catch::Contains("viscous diffusion number") && Catch::Contains("diffusion_limit"));
}

TEST_CASE("bad liquid scene input is a SceneError naming the file, line, key and fix") {
  test::TempDir dir("mps_scene");
  const std::string base = test::read_file(test::liquid_scene(kDam));
  auto load = [&](const std::string& text) { return load_liquid_scene(SceneDoc::load(dir.write("s.toml", text))); };
  // Misspelt optional key: unknown, with a suggestion.
  std::string t = base;
  t.replace(t.find("[liquid]\n"), 9, "[liquid]\ngama = 0.01\n");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("s.toml:") && Catch::Contains("gama") && Catch::Contains("gamma") &&
                                   Catch::Contains("Fix:"));
  // Misspelt required key: unknown, with the required key it most likely is (not "missing").
  t = base;
  t.replace(t.find("viscosity ="), 9, "viscosty");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("unknown key 'viscosty'") && Catch::Contains("did you mean 'viscosity'"));
  // Left out: missing.
  t = base;
  t.replace(t.find("viscosity ="), 9, "# viscosity");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("missing required key 'viscosity'"));
  // Unknown geometry type.
  t = base;
  t.replace(t.find("\"tank\""), 6, "\"bowl\"");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("geometry.type") && Catch::Contains("Fix:"));
  // A periodic channel whose length is not a whole number of spacings.
  t = base;
  t.replace(t.find("\"tank\""), 6, "\"channel\"");
  t.replace(t.find("hi = [0.584"), 11, "hi = [0.580");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("geometry.hi") && Catch::Contains("multiple of l0"));
  // A pipe in 2D.
  t = base;
  t.replace(t.find("\"tank\""), 6, "\"pipe\"");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("liquid.dim = 3"));
  // No liquid placed.
  t = base.substr(0, base.find("[[fluid]]"));
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("places no liquid"));
  // A time step so short that the duration is more steps than a run can count (it wrapped the count):
  // 1e-300 s is below the step's interval; 1e-15 s is within it, and 100 s of it are 1e17 steps.
  const std::string dt = "dt = ";
  t = base;
  t.insert(t.find(dt) + dt.size(), "1e-300 # ");
  t.replace(t.find("[run]\n"), 6, "[run]\nallow_unstable_dt = true\n");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("run.dt") && Catch::Contains("[1e-15, 1000]"));
  t = base;
  t.insert(t.find(dt) + dt.size(), "1e-15 # ");
  t.insert(t.find("duration = ") + 11, "100 # ");
  t.replace(t.find("[run]\n"), 6, "[run]\nallow_unstable_dt = true\n");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("run.duration") && Catch::Contains("at most 1e15 steps"));
  // A geometry of 1e5 m (1e10, 1e30: the same) where 0.584 m was meant: refused before any node is
  // made (it allocated > 5 GB, spun, or overflowed to 0 nodes and 'completed').
  for (const char* far : {"1e5", "1e10", "1e30"}) {
    t = base;
    t.replace(t.find("hi = [0.584"), 11, std::string("hi = [") + far);
    REQUIRE_THROWS_WITH(load(t), Catch::Contains("geometry.hi") && Catch::Contains("half this machine's memory"));
  }
  // A density or body force of 1e308 ran and failed in the pressure solve or as a stability stop:
  // refused at their keys.
  t = base;
  t.replace(t.find("density = "), std::string("density = ").size(), "density = 1e308 #");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("liquid.density") && Catch::Contains("Fix:"));
  t = base;
  t.replace(t.find("[run]"), 5, "[run]\nbody_force = [1e308, 0.0, 0.0]");
  REQUIRE_THROWS_WITH(load(t), Catch::Contains("run.body_force") && Catch::Contains("more than the 200 g"));
  // A spacing larger than the geometry (1e308 m used to fail with no fix at all): past the lengths'
  // interval, refused there; within it, against the geometry.
  t = base;
  {
    const std::size_t at = t.find("l0 = ");
    t.replace(at, t.find('\n', at) - at, "l0 = 1e308");
    REQUIRE_THROWS_WITH(load(t), Catch::Contains("liquid.l0") && Catch::Contains("out of range"));
    t.replace(at, t.find('\n', at) - at, "l0 = 100");
    REQUIRE_THROWS_WITH(load(t), Catch::Contains("liquid.l0") && Catch::Contains("not smaller than the geometry"));
  }
  // A block thinner than one spacing places no node: refused when the nodes are made (check makes them).
  t = base;
  const std::size_t hi = t.find("hi = [", t.find("[[fluid]]"));
  t.replace(hi, t.find(']', hi) - hi + 1, "hi = [0.146, 0.0001, 0.0]");
  // Located at the first [[fluid]] table, as every scene error is.
  std::string fluid_at = ":";  // appends: GCC 12 warns (-Wrestrict, a false positive) on ":" + std::string
  fluid_at += std::to_string(std::count(t.begin(), t.begin() + static_cast<long>(t.find("[[fluid]]")), '\n') + 1);
  fluid_at += ":";
  REQUIRE_THROWS_WITH(LiquidSimulation(load(t)), Catch::Contains(fluid_at + " the [[fluid]] blocks hold no lattice node") &&
                                                     Catch::Contains("Fix:"));
}

TEST_CASE("a run that blows up exits with code 3, a failed summary and the broken limit on stderr") {
  REQUIRE(fs::exists(GRAINFLOW_BINARY));
  test::TempDir dir("mps_blowup");
  // Eight times the scene's step, forced past the load check: the surge hits the far wall at CFL > 1.
  const std::string cmd = std::string("'") + GRAINFLOW_BINARY + "' run '" + test::liquid_scene(kDam) + "' --quiet --out '" +
                          (dir.path / "out").string() +
                          "' --set run.dt=4e-3 --set run.allow_unstable_dt=true 2> '" + (dir.path / "err.txt").string() +
                          "'";
  const int status = std::system(cmd.c_str());
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 3);
  const auto summary = nlohmann::json::parse(test::read_file(dir.path / "out" / "summary.json"));
  CHECK(summary["status"] == "failed");
  const std::string failure = summary["failure"];
  CHECK_THAT(failure, Catch::Contains("limit") && Catch::Contains("Fix:"));
  CHECK_THAT(test::read_file(dir.path / "err.txt"), Catch::Contains("error:"));
  // Rows written before the failure are on disk.
  CHECK(test::read_lines(dir.path / "out" / "series.csv").size() > 1);
}
