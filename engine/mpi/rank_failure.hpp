// A local step (writing a file) that may fail on some ranks but not others, turned into one
// outcome every rank shares, so that no rank goes on into a collective call its failed partners
// never reach (which would hang the run).
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

#include "engine/mpi/mpi_context.hpp"

namespace gf {

// Thrown on every rank when some rank failed. On rank 0, what() is every failed rank's message
// ("rank 1: cannot write ..."); on the others it points to rank 0's report.
class RankFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Collective: does nothing when `error` is empty on every rank, else throws RankFailure on all.
void share_failure(const MpiContext& mpi, const std::string& error);

// Runs f (which must call no collective) on this rank, then shares its outcome: an exception f
// throws on any rank becomes a RankFailure on every rank. Collective.
template <class F>
void on_every_rank(const MpiContext& mpi, F&& f) {
  std::string error;
  try {
    std::forward<F>(f)();
  } catch (const std::exception& e) {
    error = *e.what() ? e.what() : "unknown failure";
  }
  share_failure(mpi, error);
}

}  // namespace gf
