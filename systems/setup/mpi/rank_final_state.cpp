#include "systems/setup/mpi/rank_final_state.hpp"

#include "engine/mpi/rank_failure.hpp"
#include "systems/fill/state_csv.hpp"
#include "systems/setup/mpi/gathered_grains.hpp"

namespace gf {

void write_rank_final_state(const std::filesystem::path& file, const Grains& g, const MpiContext& mpi) {
  const std::vector<StateRow> rows = gather_state_rows(g, mpi);
  on_every_rank(mpi, [&] {
    if (mpi.rank() == 0) write_state_csv(file, rows);
  });
}

}  // namespace gf
