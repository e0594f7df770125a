#include "app/mpi/rank_body_app.hpp"

#include <cstdio>

#include "engine/mpi/rank_failure.hpp"
#include "engine/run_loop.hpp"
#include "app/dem_body_app.hpp"

namespace gf {

BodyContactSplit rank_contact_split(const MpiContext& mpi) {
  BodyContactSplit split;
  split.rank = mpi.rank(), split.ranks = mpi.size();
  split.share = [&mpi](std::vector<std::byte> mine) {
    // Its own part stays here: share_outcomes reads only the others'.
    std::vector<std::vector<std::byte>> send(static_cast<std::size_t>(mpi.size()), mine);
    send[static_cast<std::size_t>(mpi.rank())].clear();
    return mpi.exchange(send);
  };
  return split;
}

int run_rank_body_command(const CliOptions& opt, const DemScene& s, const MpiContext& mpi) {
  BodyRunHooks hooks;
  hooks.writer = mpi.rank() == 0;
  hooks.ranks = mpi.size();
  hooks.program = "grainflow_mpi";
  hooks.install = [&mpi](World& world) { world.resources.emplace<BodyContactSplit>(rank_contact_split(mpi)); };
  hooks.together = [&mpi](const std::function<void()>& f) { on_every_rank(mpi, f); };
  install_stop_agreement([&mpi](bool mine) { return mpi.max(mine ? 1.0 : 0.0) > 0.0; });
  int rc = 2;
  try {
    rc = run_body_command(opt, s, hooks);
  } catch (const RankFailure& e) {
    if (mpi.rank() == 0) std::fprintf(stderr, "grainflow_mpi: error: %s\n", e.what());
  }
  install_stop_agreement({});
  return rc;
}

}  // namespace gf
