// grainflow: the command-line entry. Thread count is fixed here, once, for the whole process.
#include <cstdio>
#include <exception>
#include <memory>

#include <tbb/global_control.h>
#include <tbb/info.h>

#include "app/cli.hpp"
#include "app/rank_launch.hpp"
#include "engine/run_loop.hpp"

int main(int argc, char** argv) {
  gf::CliOptions opt;
  try {
    opt = gf::parse_cli(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow: %s\n%s", e.what(), gf::usage().c_str());
    return 2;
  }
  if (opt.command == "help") {
    std::printf("%s", gf::usage().c_str());
    return 0;
  }
  if (opt.command == "version") {
    std::printf("%s", gf::version_line().c_str());
    return 0;
  }
  // Under an MPI launcher with several ranks, the run is grainflow_mpi's (rank_launch.hpp); `check`
  // writes nothing and runs here.
  if (const auto ranks = gf::launched_ranks(); ranks && *ranks > 1 && opt.command == "run") {
    const std::string why = gf::hand_over_to_ranks(argc, argv);
    std::fprintf(stderr, "grainflow: started on %d ranks, and the run on several ranks is grainflow_mpi's: %s\n", *ranks,
                 why.c_str());
    return 2;
  }
  const int threads = opt.threads > 0 ? opt.threads : tbb::info::default_concurrency();
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
  gf::install_stop_handlers();
  try {
    return opt.command == "run" ? gf::run_command(opt) : gf::check_command(opt);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "grainflow: error: %s\n", e.what());
    return 1;
  }
}
