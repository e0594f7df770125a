// The coupled step (systems/coupling/coupled_step.hpp) and its scene (systems/setup/coupled_scene.hpp):
// the grains' impulse from the liquid and the liquid's reaction cancel to rounding over every step;
// each grain's momentum changes by that impulse and its weight; the step is one graph with the DEM
// sub-steps inside; `check` prints both parts and the coupling, `run` writes series.csv and summary.json;
// a run stopped and resumed from its checkpoint goes on bit for bit; grains wrap only along the liquid's
// periodic axis; bad coupling keys are refused naming file, line, key and fix.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "engine/scene.hpp"
#include "systems/coupling/coupled_step.hpp"
#include "systems/setup/coupled_simulation.hpp"
#include "tests/test_support.hpp"

using Catch::Contains;

namespace {

// The shared tank of liquid with three grains (tests/test_support.hpp).
std::string scene(const std::string& coupling = "substeps = 16\nsmoothing_radius = 0.0075\n",
                  const std::string& extra = "") {
  return gf::test::coupled_tank_scene(coupling, extra);
}

double norm(const gf::V3<double>& a) { return std::sqrt(gf::dot(a, a)); }

gf::V3<double> momentum(gf::Grains& g) {
  gf::V3<double> p{0, 0, 0};
  for (std::size_t i = 0; i < g.n_owned; ++i) p = p + g.mass.m[i] * gf::V3<double>{g.vel.x[i], g.vel.y[i], g.vel.z[i]};
  return p;
}

// The 1-based line of the first line of `text` that starts with `key`.
int line_of(const std::string& text, const std::string& key) {
  int line = 1;
  for (std::size_t at = 0; at < text.size(); at = text.find('\n', at) + 1, ++line)
    if (text.compare(at, key.size(), key) == 0) return line;
  return 0;
}

std::string load_error(const std::string& text) {
  try {
    gf::load_coupled_scene(gf::SceneDoc::parse(text, "scene.toml"));
  } catch (const gf::SceneError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("coupled step: grain impulse and liquid reaction cancel to rounding, step by step", "[coupled]") {
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_text(scene());
  gf::World& w = sim.world();
  gf::Grains& g = w.grains;
  REQUIRE(g.n_owned == 3);
  const auto& c = w.resources.get<gf::CouplingState>();
  double mass = 0;
  for (std::size_t i = 0; i < g.n_owned; ++i) mass += g.mass.m[i];
  sim.prime();
  for (int step = 0; step < 10; ++step) {
    const gf::V3<double> p0 = momentum(g);
    sim.step_once();
    const gf::V3<double> dp = momentum(g) - p0;
    const gf::V3<double> weight = (mass * w.clock.dt) * gf::V3<double>{0.0, -9.81, 0.0};
    INFO("step " << step << ": grain impulse " << c.grain_impulse.y << " N s, reaction " << c.reaction_impulse.y);
    REQUIRE(norm(c.grain_impulse) > 0.0);
    CHECK(norm(c.grain_impulse + c.reaction_impulse) <= 1e-13 * norm(c.grain_impulse));
    // The grains lie farther than h from the walls: the whole reaction reaches fluid nodes.
    CHECK(norm(c.fluid_reaction - c.reaction_impulse) <= 1e-13 * norm(c.grain_impulse));
    // Three grains apart, no contacts: each one's momentum changes by its weight and the liquid's impulse.
    CHECK(norm(dp - weight - c.grain_impulse) <= 1e-9 * norm(weight));
  }
}

TEST_CASE("coupled step: share_with = fluid_nodes keeps a grain beside a wall off the wall's nodes", "[coupled]") {
  // Three grains against the floor (centres below 3 mm, within h = 7.5 mm of the floor's wall nodes).
  const std::string low = "[[fill]]\nkind = \"random\"\n"
                          "region = { shape = \"box\", lo = [0.01, 0.0, 0.01], hi = [0.02, 0.004, 0.02] }\n";
  auto against_floor = [&](const std::string& share) {
    std::string text = scene("substeps = 16\nsmoothing_radius = 0.0075\n" + share);
    text.replace(text.find("[[fill]]"), text.find("count =") - text.find("[[fill]]"), low);
    return gf::CoupledSimulation::from_text(text);
  };
  for (const bool fluid_only : {false, true}) {
    CAPTURE(fluid_only);
    gf::CoupledSimulation sim = against_floor(fluid_only ? "share_with = \"fluid_nodes\"\n" : "");
    gf::World& w = sim.world();
    sim.prime();
    sim.step_once();
    const auto& c = w.resources.get<gf::CouplingState>();
    const auto& f = w.tables.get<gf::FluidNodes>();
    double on_walls = 0;
    for (std::size_t k = 0; k < c.shares.node.size(); ++k)
      if (f.kind[c.shares.node[k]] != gf::kFluid) on_walls += c.shares.share[k];
    // Momentum is conserved either way; with the wall rule it all stays in the liquid.
    CHECK(norm(c.grain_impulse + c.reaction_impulse) <= 1e-13 * norm(c.grain_impulse));
    if (fluid_only) {
      CHECK(on_walls == 0.0);
      CHECK(norm(c.fluid_reaction - c.reaction_impulse) <= 1e-13 * norm(c.grain_impulse));
    } else {
      // Without it a part of each grain's share (and of its reaction) goes to the floor's nodes.
      CHECK(on_walls > 0.1);
      CHECK(norm(c.fluid_reaction - c.reaction_impulse) > 0.05 * norm(c.grain_impulse));
    }
  }
}

TEST_CASE("coupled scene: the liquid's eddy viscosity stays out of the drag law", "[coupled]") {
  // The drag and the rotational drag read the liquid's molecular viscosity: an eddy viscosity stands for
  // momentum that turbulence mixes, not for a thicker liquid around a grain.
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_text(scene(), {"liquid.eddy_viscosity=1.0e-4"});
  const gf::LiquidParams& p = sim.scene().liquid.params;
  REQUIRE(p.eddy_viscosity == 1.0e-4);
  const auto& c = sim.world().resources.get<gf::CouplingState>();
  CHECK(c.liquid.props.viscosity == p.rho * p.nu);
}

TEST_CASE("coupled step: one graph, the DEM sub-steps inside the liquid's step", "[coupled]") {
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_text(scene());
  const std::vector<std::string> outer = sim.step().names();
  REQUIRE(outer.size() >= 4);
  CHECK(outer[0] == "coupling_prepare");
  CHECK(outer[1] == "dem_substeps");
  CHECK(outer[2] == "liquid_reaction");
  CHECK(outer[3] == "neighbour_search");
  const std::vector<std::string> inner = sim.dem_substeps().inner().names();
  CHECK(std::find(inner.begin(), inner.end(), "liquid_force") != inner.end());
  CHECK(sim.dem_substeps().substeps() == 16);
  CHECK(sim.scene().dem.dt == Approx(5.0e-4 / 16).epsilon(1e-15));
  sim.advance(2);
  CHECK(sim.world().clock.step == 2);
  CHECK(sim.world().clock.t == Approx(1.0e-3).epsilon(1e-15));
}

namespace {

// The tank made a channel periodic along x over [0, 0.03] m, its grains periodic over `period`, read from
// grain.csv beside the scene, the box wall a floor.
std::string periodic_channel(const std::string& period) {
  std::string s = scene();
  s.replace(s.find("type = \"tank\""), 13, "type = \"channel\"");
  s.replace(s.find("hi = [0.03, 0.04, 0.03]"), 23, "hi = [0.03, 0.03, 0.03]");
  const std::string fill = s.substr(s.find("[[fill]]"), s.find("[coupling]") - s.find("[[fill]]"));
  s.replace(s.find(fill), fill.size(), "[[fill]]\nkind = \"file\"\npath = \"grain.csv\"\ntypes = { 1 = \"glass\" }\n");
  s.replace(s.find("type = \"box\""), 13, "type = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]");
  s.erase(s.find("lo = [0.0, 0.0, 0.0]\nhi = [0.03, 0.04, 0.03]\n[[fill]]"), 44);
  return s + "[periodic]\nx = " + period + "\n";
}

}  // namespace

TEST_CASE("coupled scene: grains periodic along the liquid's periodic axis, over its period only", "[coupled]") {
  gf::test::TempDir dir("coupled_periodic");
  dir.write("grain.csv", "id,type,diameter,x,y,z,vx,vy,vz\n0,1,0.002,0.0295,0.015,0.015,0.5,0,0\n");
  const auto load = [&](const std::string& text) {
    dir.write("scene.toml", text);
    try {
      return gf::CoupledSimulation::from_file(dir.path / "scene.toml").world().grains.n_owned == 1 ? std::string("loaded") : "no grain";
    } catch (const gf::SceneError& e) {
      return std::string(e.what());
    }
  };
  CHECK_THAT(load(periodic_channel("[0.0, 0.02]")), Contains("'periodic.x'") && Contains("differs from the liquid's") &&
                                                       Contains("set x = [0, 0.03]"));
  std::string along_z = periodic_channel("[0.0, 0.03]");
  along_z.replace(along_z.rfind("x = "), 4, "z = ");
  CHECK_THAT(load(along_z), Contains("'periodic.z'") && Contains("periodic along x only"));
  REQUIRE(load(periodic_channel("[0.0, 0.03]")) == "loaded");
  // The grain crosses the face at 0.5 m/s within the run: it comes back in at x = 0, and the liquid's
  // reaction still cancels its impulse each step (its kernel reaching across the face).
  gf::CoupledSimulation sim = gf::CoupledSimulation::from_file(dir.path / "scene.toml");
  const auto& c = sim.world().resources.get<gf::CouplingState>();
  sim.prime();
  for (int step = 0; step < 8; ++step) {
    sim.step_once();
    CHECK(norm(c.grain_impulse + c.reaction_impulse) <= 1e-13 * norm(c.grain_impulse));
  }
  const double x = sim.world().grains.pos.x[0];
  CHECK(x < 0.002);  // 0.0295 + 8 x 5e-4 s x ~0.5 m/s, wrapped
}

TEST_CASE("coupled scene: sub-steps computed from the DEM step limit when not given", "[coupled]") {
  const gf::CoupledScene s = gf::load_coupled_scene(gf::SceneDoc::parse(scene("smoothing_radius = 0.0075\n"), "scene.toml"));
  CHECK(s.coupling.substeps_computed);
  const double limit = s.dem.dt_safety * s.dem.critical.period;
  CHECK(s.coupling.substeps == static_cast<int>(std::ceil(5.0e-4 / limit)));
  CHECK(s.dem.dt <= limit);
  CHECK(s.coupling.drag == &gf::drag_law("ergun_wen_yu"));
}

TEST_CASE("coupled scene: bad keys are refused with file, line, key and fix", "[coupled]") {
  struct Bad {
    std::string coupling, extra, key, says;
  };
  const std::vector<Bad> cases = {
      {"substeps = 2\nsmoothing_radius = 0.0075\n", "", "coupling.substeps", "set substeps >="},
      {"smoothing_radius = 0.001\n", "", "coupling.smoothing_radius", "shorter than the node spacing"},
      {"smoothing_radius = 0.0075\ndrag = \"stokes\"\n", "", "coupling.drag", "ergun_wen_yu"},
      {"smoothing_radius = 0.0075\nsubstep = 16\n", "", "coupling.substep", "substeps"},
      {"smoothing_radius = 0.0075\nmodified_pressure = true\n", "", "coupling.modified_pressure", "box"},
      {"smoothing_radius = 0.0075\n", "[settle]\ntime = 0.1\n", "settle", "settling"},
      {"smoothing_radius = 0.0075\n", "[periodic]\nx = [0.0, 0.03]\n", "periodic.x", "the liquid does not"},
  };
  for (const Bad& b : cases) {
    const std::string text = scene(b.coupling, b.extra);
    const std::string leaf = b.key.substr(b.key.find('.') + 1);
    const int line = line_of(text, leaf.empty() || b.key.find('.') == std::string::npos ? "[" + b.key : leaf);
    const std::string msg = load_error(text);
    INFO(msg);
    CHECK_THAT(msg, Contains("scene.toml:" + std::to_string(line) + ":") && Contains("'" + b.key + "'") &&
                        Contains("Fix:") && Contains(b.says));
  }
  // A coupled scene states its gravity; its liquid is 3D.
  std::string no_gravity = scene();
  no_gravity.erase(no_gravity.find("gravity = "), std::string("gravity = [0.0, -9.81, 0.0]\n").size());
  CHECK_THAT(load_error(no_gravity), Contains("'run.gravity'") && Contains("Fix:"));
  std::string flat = scene();
  flat.replace(flat.find("dim = 3"), 7, "dim = 2");
  CHECK_THAT(load_error(flat), Contains("'liquid.dim'") && Contains("set dim = 3"));
}

TEST_CASE("coupled scene through the command line: check prints both parts, run writes the series and frames", "[coupled][cli]") {
  gf::test::TempDir dir("coupled_cli");
  const std::string file = dir.write("coupled.toml", scene("substeps = 16\nsmoothing_radius = 0.0075\n",
                                                            "[output]\nseries_interval = 1.0e-3\nframe_interval = 1.0e-3\n")).string();
  const gf::test::Exit check = gf::test::run_cli(dir, "check " + gf::test::quote(file));
  INFO(check.out << check.err);
  REQUIRE(check.code == 0);
  CHECK_THAT(check.out, Contains("valid") && Contains("liquid: MPS, 3D") && Contains("grains: 3 in 1 species") &&
                            Contains("k = 16 DEM sub-steps") && Contains("smoothing radius h = 0.0075 m") &&
                            Contains("drag ergun_wen_yu") && Contains("dem_substeps") && Contains("liquid_force") &&
                            Contains("liquid/frames.pvd, grains/frames.pvd"));
  const std::string out = (dir.path / "run").string();
  const gf::test::Exit run = gf::test::run_cli(dir, "run " + gf::test::quote(file) + " --out " + gf::test::quote(out) +
                                                        " --steps 4 --threads 1 --quiet");
  INFO(run.err);
  REQUIRE(run.code == 0);
  const std::vector<std::string> rows = gf::test::read_lines(dir.path / "run" / "series.csv");
  REQUIRE(rows.size() == 4);  // the header, t = 0, 1 ms and 2 ms
  CHECK_THAT(rows[0], Contains("kinetic_energy") && Contains("grain_vy") && Contains("grain_kinetic_energy") &&
                          Contains("impulse_balance"));
  // The box's loads at the same times as the series' rows.
  const std::vector<std::string> walls = gf::test::read_lines(dir.path / "run" / "walls.csv");
  REQUIRE(walls.size() == 4);
  CHECK_THAT(walls[0], Contains("time,box-x.fx") && Contains("box-y.power"));
  // Frames of both parts at t = 0, 1 and 2 ms: the liquid's nodes with pressure, the grains as a DEM run writes them.
  for (const char* part : {"liquid", "grains"}) {
    CAPTURE(part);
    const std::string pvd = gf::test::read_file(dir.path / "run" / part / "frames.pvd");
    CHECK_THAT(pvd, Contains("frame_000002.vtp") && !Contains("frame_000003.vtp"));
  }
  CHECK_THAT(gf::test::read_file(dir.path / "run" / "liquid" / "frames" / "frame_000001.vtp"),
             Contains("Name=\"pressure\"") && Contains("Name=\"number_density\""));
  CHECK_THAT(gf::test::read_file(dir.path / "run" / "grains" / "frames" / "frame_000001.vtp"), Contains("NumberOfPoints=\"3\""));
  const std::string summary = gf::test::read_file(dir.path / "run" / "summary.json");
  CHECK_THAT(summary, Contains("\"status\": \"completed\"") && Contains("\"substeps\": 16") &&
                          Contains("\"drag\": \"ergun_wen_yu\"") && Contains("liquid_force"));
}

TEST_CASE("coupled run stopped and resumed from its checkpoint goes on bit for bit", "[coupled][cli]") {
  // 8 liquid steps at once, and 4 then 4 more from the checkpoint written at the end of the first piece:
  // series.csv, walls.csv, the last frames of both parts and the grains' final state are the same bytes.
  gf::test::TempDir dir("coupled_resume");
  const std::string file = dir.write("coupled.toml", scene("substeps = 16\nsmoothing_radius = 0.0075\n",
                                                            "[output]\nseries_interval = 1.0e-3\nframe_interval = 1.0e-3\n"
                                                            "checkpoint_interval = 1.0e-3\n")).string();
  const auto run = [&](const std::string& out, const std::string& more) {
    const gf::test::Exit e = gf::test::run_cli(dir, "run " + gf::test::quote(file) + " --out " +
                                                        gf::test::quote((dir.path / out).string()) + " --threads 1 --quiet " + more);
    INFO(e.err);
    REQUIRE(e.code == 0);
  };
  run("whole", "--steps 8");
  run("pieces", "--steps 4");
  const std::string ckpt = (dir.path / "pieces" / "checkpoints" / "checkpoint.gfc").string();
  run("pieces", "--steps 8 --resume " + gf::test::quote(ckpt));
  for (const std::string f : {"series.csv", "walls.csv", "final_state.csv", "liquid/frames/frame_000004.vtp",
                              "grains/frames/frame_000004.vtp", "liquid/frames.pvd", "grains/frames.pvd"}) {
    CAPTURE(f);
    const std::string whole = gf::test::read_file(dir.path / "whole" / f);
    REQUIRE(!whole.empty());
    CHECK(gf::test::read_file(dir.path / "pieces" / f) == whole);
  }
  CHECK_THAT(gf::test::read_file(dir.path / "pieces" / "summary.json"), Contains("resumed_from"));
  // Another sub-step count is refused naming what differs.
  const gf::test::Exit other = gf::test::run_cli(dir, "run " + gf::test::quote(file) + " --set coupling.substeps=20 --out " +
                                                          gf::test::quote((dir.path / "other").string()) + " --resume " + gf::test::quote(ckpt));
  CHECK(other.code != 0);
  CHECK_THAT(other.err, Contains("16 DEM sub-steps") && Contains("Fix:"));
}
