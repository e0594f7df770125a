#include "engine/mpi/rank_failure.hpp"

#include <cstdint>
#include <vector>

namespace gf {

void share_failure(const MpiContext& mpi, const std::string& error) {
  if (mpi.max(static_cast<std::int64_t>(error.empty() ? 0 : 1)) == 0) return;
  const auto* b = reinterpret_cast<const std::byte*>(error.data());
  const std::vector<std::vector<std::byte>> all = mpi.gather(std::vector<std::byte>(b, b + error.size()), 0);
  std::string report;
  for (std::size_t r = 0; r < all.size(); ++r) {
    if (all[r].empty()) continue;
    if (!report.empty()) report += "; ";
    report += "rank " + std::to_string(r) + ": ";
    report.append(reinterpret_cast<const char*>(all[r].data()), all[r].size());
  }
  if (mpi.rank() != 0) report = "another rank failed (rank 0 reports which and why)";
  throw RankFailure(report);
}

}  // namespace gf
