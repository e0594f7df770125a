// Checkpoints of a run on several ranks (rank_checkpoints.hpp, RankSimulation::save and restore):
// a run stopped at a checkpoint and resumed ends byte for byte as the run that was not stopped (in a
// box, and in a channel with periodic faces);
// a missing or corrupt part, an index of another rank count and a file that is no index stop every
// rank with the file named.
#include <catch2/catch.hpp>

#include <fstream>
#include <string>

#include "engine/mpi/rank_failure.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"
#include "systems/output/mpi/rank_checkpoint_index.hpp"
#include "systems/setup/mpi/rank_checkpoints.hpp"
#include "systems/setup/mpi/rank_outputs.hpp"
#include "tests/mpi/mpi_test_support.hpp"
#include "tests/mpi/rank_outputs_support.hpp"

namespace {

namespace fs = std::filesystem;

// 300 1 mm and 6 3 mm grains dropped into a 40 x 20 x 20 mm box under strong gravity: within 200
// steps they hold pair and wall springs, rebuild their lists and migrate between the ranks.
std::string dropped_grains() {
  return "[run]\ndt = 1.0e-5\nduration = 0.002\nskin = 1.5e-4\nmax_overlap = 0.5\ngravity = [0.0, -400.0, 0.0]\n"
         "[[species]]\nname = \"small\"\ndiameter = 1.0e-3\ndensity = 2500.0\n"
         "[[species]]\nname = \"large\"\ndiameter = 3.0e-3\ndensity = 2500.0\n"
         "[contact]\nmodel = \"linear_spring_dashpot\"\nkn = 1000.0\nkt = 600.0\nkr = 1.0e-5\n"
         "en = 0.3\net = 0.3\ner = 0.3\nfriction = 0.3\nrolling_friction = 5.0e-5\n"
         "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.02, 0.02]\n"
         "[[fill]]\nkind = \"random\"\nseed = 7\n"
         "region = { shape = \"box\", lo = [0.0, 0.0, 0.0], hi = [0.04, 0.004, 0.02] }\n"
         "count = { small = 300, large = 6 }\n"
         "[output]\nseries_interval = 0.0001\nframe_interval = 0.0005\ncheckpoint_interval = 0.0005\n";
}

// The same grains in a channel periodic along x (a floor, a lid and side planes, gravity tilted along
// x): ghost rows across the faces, each with its shift, are part of every rank's state.
std::string periodic_grains() {
  std::string s = dropped_grains();
  const std::string box = "[[wall]]\ntype = \"box\"\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.02, 0.02]\n";
  std::string planes;
  for (const char* w : {"[0.0, 0.0, 0.0]\nnormal = [0.0, 1.0, 0.0]", "[0.0, 0.02, 0.0]\nnormal = [0.0, -1.0, 0.0]",
                        "[0.0, 0.0, 0.0]\nnormal = [0.0, 0.0, 1.0]", "[0.0, 0.0, 0.02]\nnormal = [0.0, 0.0, -1.0]"})
    planes += std::string("[[wall]]\ntype = \"plane\"\npoint = ") + w + "\n";
  s.replace(s.find(box), box.size(), planes + "[periodic]\nx = [0.0, 0.04]\n");
  const std::string from = "gravity = [0.0, -400", to = "gravity = [200.0, -400";
  s.replace(s.find(from), from.size(), to);
  return s;
}

fs::path fresh_folder(const gf::MpiContext& mpi, const std::string& name) {
  const fs::path dir = fs::current_path() / "rank_checkpoint_test_out" / (std::to_string(mpi.size()) + "_ranks") / name;
  if (mpi.rank() == 0) fs::remove_all(dir);
  mpi.barrier();
  return dir;
}

// A run's parts, as grainflow_mpi puts them together.
struct Run {
  gf::RankSimulation sim;
  gf::RankOutputs out;
  gf::RankCheckpoints checkpoints;
  Run(const fs::path& dir, const gf::MpiContext& mpi, const std::string& scene,
      std::optional<gf::RankOutputRows> rows = std::nullopt)
      : sim(gf::RankSimulation::from_text(scene, mpi)),
        out(sim.scene(), dir, mpi, rows),
        checkpoints({dir, sim.scene().output.checkpoint_interval, false}, mpi) {}

  // The main stage up to step `last`: the outputs, then the checkpoints, observe its start and every
  // step; then the checkpoint at the end and the last row, frame and final_state.csv.
  void run_to(std::int64_t last) {
    out.observe(sim.world());
    checkpoints.observe(sim, out);
    while (sim.world().clock.step < last) {
      sim.advance(1);
      out.observe(sim.world());
      checkpoints.observe(sim, out);
    }
    if (!checkpoints.holds(last)) checkpoints.write(sim, out);
    out.finish(sim.world());
  }
};

// Resumes the run whose index is `index` into `dir`, as grainflow_mpi --resume does.
std::unique_ptr<Run> resumed(const fs::path& dir, const fs::path& index, const gf::MpiContext& mpi,
                             const std::string& scene = dropped_grains()) {
  const std::unique_ptr<gf::CheckpointReader> part = gf::open_rank_part(index, mpi);
  auto run = std::make_unique<Run>(dir, mpi, scene, gf::RankOutputs::written_rows(*part));
  run->sim.restore(*part);
  run->out.restore(*part);
  run->checkpoints.restore(*part, index);
  return run;
}

// The message every rank gets from opening `index` (empty when it opens).
std::string refusal(const fs::path& index, const gf::MpiContext& mpi) {
  try {
    gf::open_rank_part(index, mpi);
  } catch (const gf::RankFailure& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

namespace {

// Runs `scene` to step `end` whole, and stopped at step `stop` (7 steps past a series row, 37 past a
// checkpoint) then resumed to `end`: the same files.
void check_resume(const std::string& scene, const std::string& name, std::int64_t stop, std::int64_t end) {
  const gf::MpiContext& mpi = gf::test::test_world();
  const fs::path whole = fresh_folder(mpi, name + "_whole"), split = fresh_folder(mpi, name + "_split");
  Run(whole, mpi, scene).run_to(end);
  Run(split, mpi, scene).run_to(stop);
  const fs::path index = split / "checkpoints" / gf::kRankIndexName;
  std::unique_ptr<Run> rest = resumed(split, index, mpi, scene);
  CHECK(rest->sim.world().clock.step == stop);
  CHECK(rest->sim.total_grains() == 306);
  rest->run_to(end);
  if (mpi.rank() == 0) {
    for (const char* file : {"final_state.csv", "series.csv", "frames.pvd"}) {
      INFO(file);
      CHECK(gf::test::slurp(whole / file) == gf::test::slurp(split / file));
    }
    CHECK(gf::test::read_csv(split / "series.csv").rows.size() == static_cast<std::size_t>(end / 10 + 1));
    // Only the latest set is kept: the parts written where the run was halted went when the next index
    // replaced them.
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(split / "checkpoints")) files += e.is_regular_file() ? 1 : 0;
    CHECK(files == static_cast<std::size_t>(mpi.size()) + 1);
    CHECK(fs::exists(split / "checkpoints" / gf::rank_part_name(end, mpi.size() - 1)));
  }
}

}  // namespace

TEST_CASE("a run stopped at a checkpoint and resumed ends byte for byte as the run that was not",
          "[mpi][rank_checkpoint]") {
  // Stopped at step 137, between two series rows, two frames and two checkpoints.
  check_resume(dropped_grains(), "box", 137, 200);
}

TEST_CASE("a periodic run stopped at a checkpoint and resumed ends byte for byte as the run that was not",
          "[mpi][rank_checkpoint][periodic]") {
  // Stopped when the grains have landed and slide along x, touching across the faces.
  check_resume(periodic_grains(), "periodic", 1137, 1200);
}

TEST_CASE("a missing or corrupt part stops every rank, naming the file", "[mpi][rank_checkpoint]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  const fs::path dir = fresh_folder(mpi, "damaged");
  Run(dir, mpi, dropped_grains()).run_to(20);
  const fs::path index = dir / "checkpoints" / gf::kRankIndexName;
  const fs::path part = dir / "checkpoints" / gf::rank_part_name(20, mpi.size() - 1);
  REQUIRE(refusal(index, mpi).empty());

  if (mpi.rank() == 0) {  // one byte in the middle of the last rank's part changed
    std::fstream f(part, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(static_cast<std::streamoff>(fs::file_size(part) / 2));
    const char c = static_cast<char>(f.get());
    f.seekp(static_cast<std::streamoff>(fs::file_size(part) / 2));
    f.put(static_cast<char>(c ^ 0x5a));
  }
  mpi.barrier();
  std::string why = refusal(index, mpi);
  REQUIRE(!why.empty());
  if (mpi.rank() == 0) {
    CHECK(has(why, "rank " + std::to_string(mpi.size() - 1) + ": " + part.string()));
    CHECK(has(why, "checksum does not match"));
  }

  if (mpi.rank() == 0) fs::remove(part);
  mpi.barrier();
  why = refusal(index, mpi);
  REQUIRE(!why.empty());
  if (mpi.rank() == 0) CHECK(has(why, part.string() + ": cannot read the checkpoint"));
  CHECK(mpi.sum(std::int64_t{1}) == mpi.size());  // every rank still in step
}

TEST_CASE("an index of another rank count, or a file that is no index, is refused with the fix",
          "[mpi][rank_checkpoint]") {
  const gf::MpiContext& mpi = gf::test::test_world();
  const fs::path dir = fresh_folder(mpi, "other_ranks");
  Run(dir, mpi, dropped_grains()).run_to(10);
  const fs::path other = dir / "checkpoints" / "more_ranks.gfc";
  const int more = mpi.size() + 1;
  if (mpi.rank() == 0) {
    gf::RankCheckpointIndex index{more, 10, 1e-4, {}};
    for (int r = 0; r < more; ++r) index.parts.push_back(gf::rank_part_name(10, r));
    gf::write_rank_index(other, index);
  }
  mpi.barrier();
  const std::string why = refusal(other, mpi);
  REQUIRE(!why.empty());
  if (mpi.rank() == 0) {
    CHECK(has(why, other.string() + ": it was written by a run on " + std::to_string(more) + " ranks"));
    CHECK(has(why, "mpiexec -n " + std::to_string(more)));
    CHECK(has(why, "final_state.csv"));
  }
  // A part given where the index goes.
  const std::string part = refusal(dir / "checkpoints" / gf::rank_part_name(10, 0), mpi);
  if (mpi.rank() == 0) CHECK(has(part, "one rank's part of a checkpoint, not its index"));
  CHECK(mpi.sum(std::int64_t{1}) == mpi.size());
}
