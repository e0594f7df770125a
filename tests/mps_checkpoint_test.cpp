// Checkpoints of liquid scenes (systems/mps/liquid_checkpoint.cpp, liquid_app.cpp): a run resumed from a checkpoint
// is bit-identical to an uninterrupted one, in memory and through the command line (node columns, series.csv,
// frames and the final checkpoint byte for byte); a checkpoint of another scene is refused naming the file and the
// fix; liquid frames carry pressure and number density per node.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "mps_support.hpp"
#include "systems/mps/liquid_checkpoint.hpp"
#include "systems/mps/liquid_outputs.hpp"
#include "systems/mps/neighbors.hpp"

using namespace gf;
namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {

// A small 2D dam break: a column of 10 x 20 nodes collapsing in a tank, so nodes move past half the skin and the
// neighbour list is rebuilt on both sides of a checkpoint.
std::string dam_scene(double column_width = 0.05) {
  return "[run]\ndt = 5.0e-4\nduration = 0.04\ngravity = [0.0, -9.81, 0.0]\ndomain_margin = 0.1\n"
         "[liquid]\ndim = 2\nl0 = 0.005\ndensity = 1000.0\nviscosity = 1.0e-6\n"
         "[geometry]\ntype = \"tank\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.15, 0.12, 0.0]\n"
         "[[fluid]]\nlo = [0.0, 0.0, 0.0]\nhi = [" + std::to_string(column_width) + ", 0.1, 0.0]\n"
         "[output]\nseries_interval = 0.005\nframe_interval = 0.005\ncheckpoint_interval = 0.01\n";
}

template <class T>
bool same_bits(const Column<T>& a, const Column<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

bool same_nodes(FluidNodes& a, FluidNodes& b) {
  bool same = true;
  std::apply([&](auto&... ca) { std::apply([&](auto&... cb) { ((same = same && same_bits(ca, cb)), ...); },
                                           b.columns()); },
             a.columns());
  return same;
}

void write_checkpoint(LiquidSimulation& sim, const fs::path& file) {
  CheckpointWriter w;
  save_liquid_state(w, sim.world(), sim.scene());
  w.write(file);
}

std::string run_args(const fs::path& scene, const fs::path& out, const std::string& more) {
  return "run " + test::quote(scene.string()) + " --out " + test::quote(out.string()) + " --quiet " + more;
}

}  // namespace

TEST_CASE("liquid checkpoint: a simulation resumed from a checkpoint is bit-identical to an uninterrupted one") {
  test::TempDir dir("mps_ckpt_mem");
  auto whole = LiquidSimulation::from_text(dam_scene());
  whole.advance(80);
  auto first = LiquidSimulation::from_text(dam_scene());
  first.advance(40);
  write_checkpoint(first, dir.path / "c.gfc");
  const std::int64_t builds_at_split = first.world().resources.get<NeighborPairs>().builds;

  auto resumed = LiquidSimulation::from_text(dam_scene());
  restore_liquid_state(CheckpointReader(dir.path / "c.gfc"), resumed.world(), resumed.scene());
  CHECK(resumed.world().clock.step == 40);
  resumed.advance(40);
  const auto& nb = resumed.world().resources.get<NeighborPairs>();
  CHECK(nb.builds > builds_at_split);  // the list was rebuilt after the split
  CHECK(nb.builds == whole.world().resources.get<NeighborPairs>().builds);
  CHECK(nb.j == whole.world().resources.get<NeighborPairs>().j);
  CHECK(resumed.world().clock.t == whole.world().clock.t);
  CHECK(resumed.world().clock.step == 80);
  CHECK(same_nodes(resumed.nodes(), whole.nodes()));
  CHECK(sample_liquid(resumed.world(), resumed.scene()) == sample_liquid(whole.world(), whole.scene()));
}

TEST_CASE("liquid checkpoint: a run in two pieces writes the same series, frames and checkpoint as one run") {
  // Also with a multigrid hierarchy kept over 7 steps: a checkpoint makes the next solve rebuild it, so the
  // resumed piece and the unbroken run build theirs at the same steps.
  const std::string solver = GENERATE(std::string(), std::string("[liquid.solver]\npreconditioner = \"multigrid\"\nmultigrid_reuse = 7\n"));
  test::TempDir dir("mps_ckpt_cli");
  const fs::path scene = dir.write("dam.toml", dam_scene() + solver);
  const fs::path one = dir.path / "one", two = dir.path / "two";
  auto a = test::run_cli(dir, run_args(scene, one, "--steps 80"));
  INFO(a.err);
  REQUIRE(a.code == 0);
  // The first piece stops at step 55 without a final checkpoint: its last one is at step 40 (0.02 s), and the
  // row and frame it wrote at step 50 must be dropped and written again by the resumed piece.
  auto b = test::run_cli(dir, run_args(scene, two, "--steps 55 --set output.checkpoint_at_end=false"));
  REQUIRE(b.code == 0);
  CHECK(test::read_lines(two / "series.csv").size() == 1 + 6);
  auto c = test::run_cli(dir, run_args(scene, two, "--steps 80 --resume " +
                                                       test::quote((two / "checkpoints" / "checkpoint.gfc").string())));
  INFO(c.err);
  REQUIRE(c.code == 0);
  CHECK_THAT(c.err, Contains("resuming from") && Contains("at step 40"));
  CHECK(test::read_lines(one / "series.csv").size() == 1 + 9);  // header, steps 0, 10, ..., 80
  CHECK(test::read_file(one / "series.csv") == test::read_file(two / "series.csv"));
  CHECK(test::read_file(one / "frames.pvd") == test::read_file(two / "frames.pvd"));
  std::size_t frames = 0;
  for (const auto& f : fs::directory_iterator(one / "frames")) {
    ++frames;
    CHECK(test::read_file(f.path()) == test::read_file(two / "frames" / f.path().filename()));
  }
  CHECK(frames == 9);
  CHECK(test::read_file(one / "checkpoints" / "checkpoint.gfc") ==
        test::read_file(two / "checkpoints" / "checkpoint.gfc"));
  const auto s = nlohmann::json::parse(test::read_file(two / "summary.json"));
  CHECK(s["steps"] == 80);
  CHECK(s["steps_this_run"] == 40);
  CHECK(s["resumed_from"]["step"] == 40);
}

TEST_CASE("liquid checkpoint: a checkpoint of another scene is refused, naming the file and the fix") {
  test::TempDir dir("mps_ckpt_other");
  auto sim = LiquidSimulation::from_text(dam_scene());
  sim.advance(2);
  const fs::path file = dir.path / "dam.gfc";
  write_checkpoint(sim, file);

  auto wider = LiquidSimulation::from_text(dam_scene(0.06));
  CHECK_THROWS_WITH(restore_liquid_state(CheckpointReader(file), wider.world(), wider.scene()),
                    Contains(file.string()) && Contains("nodes") && Contains("Fix: resume with the liquid scene"));
  auto finer = LiquidSimulation::from_text(dam_scene(), {"liquid.l0=0.0025"});
  CHECK_THROWS_WITH(restore_liquid_state(CheckpointReader(file), finer.world(), finer.scene()),
                    Contains(file.string()) && Contains("liquid.l0"));

  // A checkpoint without liquid state (a DEM run's) is refused before anything is read.
  CheckpointWriter dem;
  dem.value("clock.t", 0.0);
  dem.write(dir.path / "dem.gfc");
  CHECK_THROWS_WITH(restore_liquid_state(CheckpointReader(dir.path / "dem.gfc"), sim.world(), sim.scene()),
                    Contains("dem.gfc") && Contains("no liquid state"));

  // Through the command line: exit status 1 and the message on stderr.
  const fs::path other = dir.write("wider.toml", dam_scene(0.06));
  auto r = test::run_cli(dir, run_args(other, dir.path / "out", "--steps 4 --resume " + test::quote(file.string())));
  CHECK(r.code == 1);
  CHECK_THAT(r.err, Contains(file.string()) && Contains("Fix:"));
}

TEST_CASE("liquid frames carry pressure and number density, one value per node") {
  test::TempDir dir("mps_ckpt_vtk");
  auto sim = LiquidSimulation::from_text(dam_scene(), {"output.frame_interval=0.005"});
  sim.advance(10);
  LiquidOutputs outputs(dir.path, sim.scene(), nullptr);
  outputs.observe(sim.world());  // step 10 is on the frame grid
  REQUIRE(outputs.frames() == 1);
  const std::string vtp = test::read_file(dir.path / "frames" / "frame_000000.vtp");
  const FluidNodes& f = sim.nodes();
  CHECK_THAT(vtp, Contains("NumberOfPoints=\"" + std::to_string(f.size()) + "\""));
  const std::size_t blob = vtp.find('_', vtp.find("<AppendedData")) + 1;
  for (const auto& [name, col] : {std::pair<std::string, const ColumnD*>{"pressure", &f.p}, {"number_density", &f.n}}) {
    CAPTURE(name);
    const std::size_t at = vtp.find("Name=\"" + name + "\"");
    REQUIRE(at != std::string::npos);
    const std::size_t off = vtp.find("offset=\"", at) + 8;
    const std::size_t offset = std::stoull(vtp.substr(off, vtp.find('"', off) - off));
    std::uint64_t bytes = 0;
    std::memcpy(&bytes, vtp.data() + blob + offset, sizeof bytes);
    CHECK(bytes == f.size() * sizeof(double));
    std::vector<double> values(f.size());
    std::memcpy(values.data(), vtp.data() + blob + offset + sizeof bytes, bytes);
    CHECK(std::memcmp(values.data(), col->data(), bytes) == 0);
  }
  CHECK(std::any_of(f.p.begin(), f.p.end(), [](double p) { return p > 0; }));  // a hydrostatic pressure to show
}

TEST_CASE("liquid checkpoint keys: read as in DEM scenes, checked naming file, line, key and fix, listed by check") {
  const std::string scene = dam_scene();
  const LiquidScene s = load_liquid_scene(SceneDoc::parse(scene, "scene.toml", {"output.checkpoint_keep_all=true"}));
  CHECK(s.output.checkpoint_interval == 0.01);
  CHECK(s.output.checkpoint_keep_all);
  CHECK(s.output.checkpoint_at_end);
  std::string short_interval = scene;
  short_interval.replace(short_interval.find("checkpoint_interval = 0.01"), 26, "checkpoint_interval = 1e-4");
  CHECK_THROWS_WITH(load_liquid_scene(SceneDoc::parse(short_interval, "scene.toml")),
                    Contains("scene.toml:21:") && Contains("checkpoint_interval") &&
                        Contains("shorter than the time step") && Contains("Fix:"));

  test::TempDir dir("mps_ckpt_check");
  const fs::path file = dir.write("dam.toml", scene);
  auto r = test::run_cli(dir, "check " + test::quote(file.string()));
  REQUIRE(r.code == 0);
  CHECK_THAT(r.out, Contains("checkpoints: checkpoints/checkpoint.gfc every 0.01 s and at the end") &&
                        Contains("pressure and number density"));
}
