// Checkpoint and restart: a resumed run is bit-identical to an uninterrupted one (same thread
// count), in memory and through the command line; a run killed mid-way keeps what it wrote and
// resumes from its last checkpoint; damaged or mismatched checkpoints are refused with the fix.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include "systems/broadphase/broadphase.hpp"
#include "systems/setup/dem_checkpoint.hpp"
#include "systems/setup/dem_simulation.hpp"
#include "tests/test_support.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;
using gf::test::quote;
using gf::test::read_file;
using gf::test::read_lines;
using gf::test::run_cli;
using gf::test::TempDir;

namespace {

// The small drum poured while it turns, under strong gravity so that it packs within about 25 ms:
// grains fall, collide and shear, so the neighbour list is rebuilt and springs are carried over
// many times on both sides of a checkpoint. Pictures every 0.01 rad check that they resume too.
const std::string kDrum = gf::test::small_drum_scene(60.0, "max_overlap = 0.3\n") +  // hard landings of the pour
                          "picture_interval = 0.01\npicture_size = 200\n";

// Every core and attached column, byte for byte.
bool same_bits(gf::Grains& a, gf::Grains& b) {
  if (a.n != b.n || a.n_owned != b.n_owned) return false;
  std::vector<std::string> ab, bb;
  auto dump = [](gf::Grains& g, std::vector<std::string>& out) {
    g.for_each_core_column([&](auto& col) {
      out.emplace_back(reinterpret_cast<const char*>(col.data()), col.size() * sizeof(*col.data()));
    });
    for (const gf::RawColumn& c : g.extras.raw_columns())
      out.emplace_back(static_cast<const char*>(c.data), c.size * c.elem_size);
  };
  dump(a, ab);
  dump(b, bb);
  return ab == bb;
}

std::string scene_args(const fs::path& scene, const fs::path& out, const std::string& more) {
  return "run " + quote(scene.string()) + " --out " + quote(out.string()) + " --threads 2 --quiet " + more;
}

// Resumes the run in `out` from `ckpt` (its step `at`) to step at + 300, runs the scene from its start
// to that step in dir/whole, both with `sets` (the caller compares their files).
void resume_and_whole(const TempDir& dir, const fs::path& scene, const fs::path& out, const fs::path& ckpt,
                      std::int64_t at, const std::string& sets) {
  const std::string end = std::to_string(at + 300);
  auto r = run_cli(dir, scene_args(scene, out, "--steps " + end + sets + " --resume " + quote(ckpt.string())));
  INFO(r.err);
  REQUIRE(r.code == 0);
  auto u = run_cli(dir, scene_args(scene, dir.path / "whole", "--steps " + end + sets));
  INFO(u.err);
  REQUIRE(u.code == 0);
}

}  // namespace

TEST_CASE("checkpoint: a simulation resumed from a checkpoint is bit-identical to an uninterrupted one",
          "[checkpoint]") {
  TempDir dir("ckpt_mem");
  auto whole = gf::DemSimulation::from_text(kDrum);
  whole.advance(3500);

  auto first = gf::DemSimulation::from_text(kDrum);
  first.advance(2700);
  const auto rebuilds_at_checkpoint = first.world().resources.get<gf::BroadphaseState>().rebuilds;
  gf::CheckpointWriter w;
  gf::save_dem_state(w, first.world(), first.scene());
  w.write(dir.path / "c.gfc");

  auto resumed = gf::DemSimulation::from_text(kDrum);
  resumed.resume(gf::CheckpointReader(dir.path / "c.gfc"));
  CHECK(resumed.world().clock.step == 2700);
  resumed.advance(800);

  // The stretch after the checkpoint rebuilt the list and carried springs, or the test proves little.
  const auto& bp = whole.world().resources.get<gf::BroadphaseState>();
  REQUIRE(bp.rebuilds > rebuilds_at_checkpoint + 3);
  REQUIRE(whole.world().resources.get<gf::PairHistory>().size() > 100);
  CHECK(resumed.world().resources.get<gf::BroadphaseState>().rebuilds == bp.rebuilds);
  CHECK(resumed.world().clock.t == whole.world().clock.t);
  CHECK(same_bits(resumed.grains(), whole.grains()));
  const auto& h1 = whole.world().resources.get<gf::PairHistory>();
  const auto& h2 = resumed.world().resources.get<gf::PairHistory>();
  REQUIRE(h1.size() == h2.size());
  REQUIRE(h1.width == 6);
  for (std::size_t q = 0; q < h1.width; ++q)
    CHECK(std::memcmp(h1.value[q].data(), h2.value[q].data(), h1.size() * sizeof(double)) == 0);
}

TEST_CASE("checkpoint: grains added and removed during a run, and changes still queued, resume bit-identically",
          "[checkpoint]") {
  // A run removes two grains and adds one (applied at the next rebuild), then queues one more grain
  // and one removal and is checkpointed before they apply. Resumed into a scene whose fill gives the
  // original 420 grains, it must continue bit for bit with the run that went on, ids and all.
  TempDir dir("ckpt_rows");
  auto changes = [](gf::DemSimulation& s, double at_height) {
    gf::Grains& g = s.grains();
    const gf::SpeciesSpec& small = s.scene().species[0];
    const auto p = gf::test::free_spot(g, {-8e-3, -8e-3, -2e-3}, {8e-3, at_height, 2e-3}, 0.5e-3, 0.5e-3);
    return g.queue_insert(gf::test::grain_at(p, small.smallest(), small.density, 0));
  };
  auto whole = gf::DemSimulation::from_text(kDrum);
  whole.advance(1500);
  whole.grains().queue_remove(5);
  whole.grains().queue_remove(77);
  const std::int64_t first_new = changes(whole, 8e-3);
  whole.advance(300);
  REQUIRE(whole.grains().n_owned == 419);
  const std::int64_t second_new = changes(whole, 8e-3);
  whole.grains().queue_remove(first_new);
  REQUIRE_FALSE(whole.grains().pending.empty());
  gf::CheckpointWriter w;
  gf::save_dem_state(w, whole.world(), whole.scene());
  w.write(dir.path / "c.gfc");
  whole.advance(700);

  auto resumed = gf::DemSimulation::from_text(kDrum);
  resumed.resume(gf::CheckpointReader(dir.path / "c.gfc"));
  CHECK(resumed.grains().n_owned == 419);
  CHECK(resumed.grains().next_id == second_new + 1);
  resumed.advance(700);
  REQUIRE(whole.grains().n_owned == 419);  // one in, one out
  CHECK(same_bits(resumed.grains(), whole.grains()));
  std::vector<std::int64_t> ids(whole.grains().pid.id.begin(), whole.grains().pid.id.end());
  std::sort(ids.begin(), ids.end());
  CHECK(std::adjacent_find(ids.begin(), ids.end()) == ids.end());
  CHECK(std::binary_search(ids.begin(), ids.end(), second_new));
  CHECK_FALSE(std::binary_search(ids.begin(), ids.end(), first_new));
  CHECK_FALSE(std::binary_search(ids.begin(), ids.end(), std::int64_t{5}));
  const auto& h1 = whole.world().resources.get<gf::PairHistory>();
  const auto& h2 = resumed.world().resources.get<gf::PairHistory>();
  REQUIRE(h1.size() == h2.size());
  for (std::size_t q = 0; q < h1.width; ++q)
    CHECK(std::memcmp(h1.value[q].data(), h2.value[q].data(), h1.size() * sizeof(double)) == 0);
}

TEST_CASE("checkpoint: a run in two pieces writes the same files as one run", "[checkpoint][cli]") {
  TempDir dir("ckpt_cli");
  const fs::path scene = dir.write("drum.toml", kDrum);
  const fs::path one = dir.path / "one", two = dir.path / "two";
  // 500 steps is off the frame grid (200 steps), so the first piece ends with an extra final frame
  // and row that the resumed piece must drop.
  auto a = run_cli(dir, scene_args(scene, one, "--steps 1300 --set output.checkpoint_interval=4e-3"));
  REQUIRE(a.code == 0);
  auto b = run_cli(dir, scene_args(scene, two, "--steps 500 --set output.checkpoint_interval=4e-3"));
  REQUIRE(b.code == 0);
  REQUIRE(fs::exists(two / "checkpoints" / "checkpoint.gfc"));
  // A third folder as a run of a build that wrote no surface.csv left it.
  const fs::path three = dir.path / "three";
  fs::copy(two, three, fs::copy_options::recursive);
  fs::remove(three / "surface.csv");
  auto c = run_cli(dir, scene_args(scene, two,
                                   "--steps 1300 --set output.checkpoint_interval=4e-3 --resume " +
                                       quote((two / "checkpoints" / "checkpoint.gfc").string())));
  INFO(c.err);
  REQUIRE(c.code == 0);
  CHECK(read_file(one / "final_state.csv") == read_file(two / "final_state.csv"));
  CHECK(read_file(one / "series.csv") == read_file(two / "series.csv"));
  CHECK(read_lines(one / "series.csv").size() == 1 + 14);  // header, t = 0 .. 13 ms, and the end is on the grid
  // The free surface's rows are the series' rows, resumed the same way.
  CHECK(read_file(one / "surface.csv") == read_file(two / "surface.csv"));
  // The walls' mean loads: the resumed piece continues the checkpointed sums, so its rows are the same too.
  CHECK(read_lines(one / "walls.csv").size() == 1 + 14);
  CHECK(read_file(one / "walls.csv") == read_file(two / "walls.csv"));
  CHECK(read_lines(one / "surface.csv").size() == 1 + 14);
  // Without a surface.csv to continue, the resumed run starts one with the rows after its checkpoint.
  const fs::path ckpt3 = three / "checkpoints" / "checkpoint.gfc";
  const double t_ckpt = gf::CheckpointReader(ckpt3).value<double>("clock.t");
  auto d = run_cli(dir, scene_args(scene, three,
                                   "--steps 1300 --set output.checkpoint_interval=4e-3 --resume " +
                                       quote(ckpt3.string())));
  INFO(d.err);
  REQUIRE(d.code == 0);
  const auto all = read_lines(one / "surface.csv"), later = read_lines(three / "surface.csv");
  std::vector<std::string> expected{all[0]};
  for (std::size_t r = 1; r < all.size(); ++r)
    if (std::stod(all[r].substr(0, all[r].find(','))) > t_ckpt) expected.push_back(all[r]);
  CHECK(expected.size() > 2);
  CHECK(later == expected);
  CHECK(read_file(one / "frames.pvd") == read_file(two / "frames.pvd"));
  for (const auto& f : fs::directory_iterator(one / "frames"))
    CHECK(read_file(f.path()) == read_file(two / "frames" / f.path().filename()));
  // 13 ms at 3 rad/s is 0.039 rad: pictures at 0, 0.01, 0.02, 0.03 rad, none drawn twice.
  std::vector<std::string> pics_one, pics_two;
  for (const auto& f : fs::directory_iterator(one / "pictures")) pics_one.push_back(f.path().filename().string());
  for (const auto& f : fs::directory_iterator(two / "pictures")) pics_two.push_back(f.path().filename().string());
  std::sort(pics_one.begin(), pics_one.end());
  std::sort(pics_two.begin(), pics_two.end());
  CHECK(pics_one.size() == 4);
  CHECK(pics_one == pics_two);
  for (const auto& name : pics_one) CHECK(read_file(one / "pictures" / name) == read_file(two / "pictures" / name));
  CHECK(read_file(one / "checkpoints" / "checkpoint.gfc") == read_file(two / "checkpoints" / "checkpoint.gfc"));
}

TEST_CASE("checkpoint: a piece ending off the series' grid, and a resume that takes no step, write no row twice",
          "[checkpoint][cli]") {
  TempDir dir("ckpt_offgrid");
  const fs::path scene = dir.write("drum.toml", kDrum);
  const fs::path one = dir.path / "one", two = dir.path / "two";
  const fs::path ckpt = two / "checkpoints" / "checkpoint.gfc";
  REQUIRE(run_cli(dir, scene_args(scene, one, "--steps 1300")).code == 0);
  // 550 steps is half-way between series rows (every 100 steps): the piece's final row at 5.5 ms
  // is dropped from both files when the next piece resumes.
  REQUIRE(run_cli(dir, scene_args(scene, two, "--steps 550")).code == 0);
  auto b = run_cli(dir, scene_args(scene, two, "--steps 1300 --resume " + quote(ckpt.string())));
  INFO(b.err);
  REQUIRE(b.code == 0);
  CHECK(read_file(one / "series.csv") == read_file(two / "series.csv"));
  CHECK(read_file(one / "surface.csv") == read_file(two / "surface.csv"));
  // Resumed at its end (on the grid) with nothing left to run, the run adds no row.
  auto c = run_cli(dir, scene_args(scene, two, "--steps 1300 --resume " + quote(ckpt.string())));
  INFO(c.err);
  REQUIRE(c.code == 0);
  CHECK(read_file(one / "series.csv") == read_file(two / "series.csv"));
  CHECK(read_file(one / "surface.csv") == read_file(two / "surface.csv"));
}

TEST_CASE("checkpoint: a run killed mid-way keeps its rows and resumes from its last checkpoint",
          "[checkpoint][cli]") {
  TempDir dir("ckpt_kill");
  const fs::path scene = dir.write("drum.toml", kDrum);
  const fs::path out = dir.path / "killed";
  const fs::path series = out / "series.csv", ckpt = out / "checkpoints" / "checkpoint.gfc";
  const std::string log = (dir.path / "killed.txt").string();
  const pid_t pid = gf::test::spawn_cli({"run", scene.string(), "--out", out.string(), "--steps", "100000000",
                                         "--threads", "2", "--quiet", "--set", "output.checkpoint_interval=5e-3",
                                         "--set", "output.series_interval=1e-4"},
                                        log);
  REQUIRE(pid >= 0);
  // Kill (no chance to clean up) once two checkpoints after t = 0 exist: 160 rows of 1e-4 s.
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    const auto rows = fs::exists(series) ? read_lines(series).size() : 0;
    if (rows > 160) break;
    int status = 0;
    if (::waitpid(pid, &status, WNOHANG) == pid) FAIL("the run ended before it was killed: " << read_file(log));
    if (std::chrono::steady_clock::now() - t0 > std::chrono::seconds(60)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  REQUIRE(::kill(pid, SIGKILL) == 0);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);

  // What was written stays readable: the header and complete rows (a last row may be cut short).
  const auto rows = read_lines(series);
  REQUIRE(rows.size() > 160);
  const auto commas = std::count(rows[0].begin(), rows[0].end(), ',');
  for (std::size_t r = 1; r + 1 < rows.size(); ++r) REQUIRE(std::count(rows[r].begin(), rows[r].end(), ',') == commas);
  const gf::CheckpointReader reader(ckpt);
  const auto at = reader.value<std::int64_t>("clock.step");
  REQUIRE(at >= 1000);  // at least the checkpoint at 10 ms
  REQUIRE(at % 500 == 0);

  // Resumed to a fixed end, it matches a run that was never killed.
  resume_and_whole(dir, scene, out, ckpt, at,
                   " --set output.checkpoint_interval=5e-3 --set output.series_interval=1e-4");
  CHECK(read_file(out / "final_state.csv") == read_file(dir.path / "whole" / "final_state.csv"));
  CHECK(read_file(out / "series.csv") == read_file(dir.path / "whole" / "series.csv"));
  // The rows the killed run wrote past its checkpoint are dropped by their time.
  CHECK(read_file(out / "surface.csv") == read_file(dir.path / "whole" / "surface.csv"));
}

TEST_CASE("checkpoint: a run stopped by SIGINT between outputs resumes to the uninterrupted run's bits",
          "[checkpoint][cli]") {
  // Stopped at whatever step the signal lands on, the run's last closing kick is left to the next
  // step unless an output sampled that step: the stop must apply it before the checkpoint. The only
  // output is a series row every 100 steps (frames and pictures take long enough to write that a
  // signal would mostly land in a step they sample).
  TempDir dir("ckpt_int");
  const fs::path scene = dir.write("drum.toml", gf::test::small_drum_scene(60.0, "max_overlap = 0.3\n"));
  const fs::path out = dir.path / "stopped";
  const fs::path series = out / "series.csv", ckpt = out / "checkpoints" / "checkpoint.gfc";
  const pid_t pid = gf::test::spawn_cli({"run", scene.string(), "--out", out.string(), "--steps", "100000000",
                                         "--threads", "2", "--quiet", "--set", "output.frame_interval=0"},
                                        (dir.path / "stopped.txt").string());
  REQUIRE(pid >= 0);
  const auto t0 = std::chrono::steady_clock::now();
  while ((fs::exists(series) ? read_lines(series).size() : 0) < 8 &&
         std::chrono::steady_clock::now() - t0 < std::chrono::seconds(60))
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  std::this_thread::sleep_for(std::chrono::microseconds(1700));  // off the series' grid, most likely
  REQUIRE(::kill(pid, SIGINT) == 0);
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  const gf::CheckpointReader reader(ckpt);
  const auto at = reader.value<std::int64_t>("clock.step");
  REQUIRE(at > 0);
  INFO("stopped after step " << at);
  resume_and_whole(dir, scene, out, ckpt, at, " --set output.frame_interval=0");
  CHECK(read_file(out / "final_state.csv") == read_file(dir.path / "whole" / "final_state.csv"));
  // A stop on a sampled step (one in a hundred) leaves nothing pending and tests less: say so.
  if (at % 100 == 0) WARN("the signal landed on a step the series sampled (" << at << ")");
}

TEST_CASE("checkpoint: damaged or mismatched checkpoints are refused with the fix", "[checkpoint]") {
  TempDir dir("ckpt_bad");
  auto sim = gf::DemSimulation::from_text(kDrum);
  sim.advance(50);
  gf::CheckpointWriter w;
  gf::save_dem_state(w, sim.world(), sim.scene());
  const fs::path good = dir.path / "good.gfc";
  w.write(good);
  const std::string bytes = read_file(good);

  auto refused = [&](const std::string& content, const std::string& expect) {
    const fs::path p = dir.write("bad.gfc", content);
    try {
      gf::CheckpointReader r(p);
      auto other = gf::DemSimulation::from_text(kDrum);
      other.resume(r);
      FAIL("accepted a bad checkpoint");
    } catch (const gf::CheckpointError& e) {
      CHECK_THAT(e.what(), Contains(expect) && Contains("bad.gfc") && Contains("Fix:"));
    }
  };
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  refused(flipped, "checksum");
  refused(bytes.substr(0, bytes.size() - 1000), "checksum");
  refused("hello\n", "not a grainflow checkpoint");
  refused("", "not a grainflow checkpoint");

  // Arrays that a correct checksum cannot vouch for (a checkpoint corrupted and sealed again, found by
  // the input fuzzer): each value used as an index or as a place is checked before the run uses it
  // (a far grain once overflowed the cell count and crashed the pattern classifier).
  auto sealed = [&](auto&& corrupt, const std::string& expect) {
    auto bad = gf::DemSimulation::from_text(kDrum);
    bad.advance(50);
    corrupt(bad.grains());
    gf::CheckpointWriter wb;
    gf::save_dem_state(wb, bad.world(), bad.scene());
    wb.write(dir.path / "sealed.gfc");
    refused(read_file(dir.path / "sealed.gfc"), expect);
  };
  sealed([](gf::Grains& g) { g.pos.x[7] = 1e73; }, "a grain's centre is outside wall");
  sealed([](gf::Grains& g) { g.species.type[3] = 99; }, "a grain's species is out of range");
  sealed([](gf::Grains& g) { g.radius.r[5] = -1.0; }, "a grain's radius or mass is not a positive number");
  sealed([](gf::Grains& g) { g.pos.y[2] = std::nan(""); }, "a grain's position is not finite");

  // The same state against a scene with another step is refused; against another fill count it is
  // accepted, and the rows are the checkpoint's (grains are fed and drained during runs).
  const gf::CheckpointReader r(good);
  auto other_dt = gf::DemSimulation::from_text(kDrum, {"run.dt=5e-6"});
  CHECK_THROWS_WITH(other_dt.resume(r), Contains("run.dt") && Contains("Fix:"));
  auto other_n = gf::DemSimulation::from_text(kDrum, {"fill.0.count.small=300"});
  REQUIRE_NOTHROW(other_n.resume(r));
  CHECK(other_n.grains().n_owned == r.value<std::uint64_t>("grains.n_owned"));
  CHECK(other_n.grains().n_owned == 420);

  // Through the command line: exit status 1 and the message on stderr.
  const fs::path scene = dir.write("drum.toml", kDrum);
  auto e = run_cli(dir, scene_args(scene, dir.path / "o", "--resume " + quote((dir.path / "missing.gfc").string())));
  CHECK(e.code == 1);
  CHECK_THAT(e.err, Contains("missing.gfc") && Contains("the file does not exist"));
}
