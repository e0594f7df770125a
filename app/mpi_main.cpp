// grainflow_mpi: a DEM scene stepped on several ranks, launched by mpiexec.
//
//   mpiexec -n P grainflow_mpi run SCENE [--out DIR] [--steps N] [--threads T] [--set key=value]...
//                                  [--resume DIR/checkpoints/checkpoint_ranks.gfc] [--rebalance RATIO]
//
// (or mpiexec -n P grainflow run ..., which hands over to this program: app/rank_launch.hpp). The
// command line is grainflow's, parsed by the same code (app/cli.hpp): the same options, checks and
// messages; `grainflow_mpi check SCENE` checks on rank 0 as `grainflow check` does. A run goes
// through the run skeleton every model shares (app/run_model.hpp): grains on ranks as
// app/mpi/rank_sphere_app.hpp says, composite bodies as app/mpi/rank_body_app.hpp says (every rank
// steps the whole scene with the member contacts shared out, bit-identical to `grainflow run`; --resume
// takes DIR/checkpoints/checkpoint.gfc on any rank count, and --rebalance does not apply). Exit
// status 2 for a scene, usage or checkpoint error (every rank stops; rank 0 names the file), 3 when
// the run became unphysical or an output could not be written.
#include <cstdio>
#include <exception>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "app/cli.hpp"
#include "app/commands.hpp"
#include "app/mpi/rank_body_app.hpp"
#include "app/mpi/rank_sphere_app.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "app/out_dir.hpp"
#include "engine/run_loop.hpp"
#include "systems/setup/mpi/rank_simulation.hpp"

namespace {

// A scene on the ranks: grains (rank_sphere_app.hpp) or composite bodies (rank_body_app.hpp).
int run_ranks(const gf::CliOptions& opt, const gf::MpiContext& mpi) {
  // Rank 0 claims the output folder before any rank writes; the others wait for its verdict.
  int claimed = 0;
  if (mpi.rank() == 0) {
    try {
      gf::claim_out_dir(opt);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "grainflow_mpi: error: %s\n", e.what());
      claimed = 2;
    }
  }
  if (mpi.max(static_cast<double>(claimed)) > 0) return 2;
  gf::DemScene scene;
  try {
    scene = gf::RankSimulation::load_scene(opt.scene, opt.overrides);
  } catch (const std::exception& e) {
    // Every rank loads the same scene and fails alike: rank 0 reports.
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: %s\n", e.what());
    return 2;
  }
  if (!scene.bodies) return gf::run_rank_sphere_command(opt, std::move(scene), mpi);
  try {
    return gf::run_rank_body_command(opt, scene, mpi);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow_mpi: rank %d: %s\n", mpi.rank(), e.what());
    MPI_Abort(mpi.comm(), 2);
  }
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  gf::MpiContext mpi(&argc, &argv);
  gf::install_stop_handlers();
  gf::CliOptions opt;
  try {
    opt = gf::parse_cli(argc, argv, "grainflow_mpi");
  } catch (const gf::CliError& e) {
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: %s\n%s", e.what(), gf::usage("grainflow_mpi").c_str());
    return 2;
  }
  if (opt.command == "help" || opt.command == "version") {
    if (mpi.rank() == 0)
      std::printf("%s", (opt.command == "help" ? gf::usage("grainflow_mpi") : gf::version_line("grainflow_mpi")).c_str());
    return 0;
  }
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  if (opt.command == "check") {  // one process checks; the others wait for its verdict
    int status = 0;
    if (mpi.rank() == 0) {
      try {
        status = gf::check_command(opt);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "grainflow_mpi: error: %s\n", e.what());
        status = 1;
      }
    }
    return static_cast<int>(mpi.max(static_cast<double>(status)));
  }
  return run_ranks(opt, mpi);
}
