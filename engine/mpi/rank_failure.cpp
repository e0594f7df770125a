#include "engine/mpi/rank_failure.hpp"

#include <cstdint>
#include <vector>

namespace gf {

namespace {

// "rank 0: why; rank 1: why else", ranks that failed alike named together ("ranks 0, 1: why").
std::string joined(const std::vector<std::vector<std::byte>>& all) {
  std::vector<std::string> why;
  std::vector<std::vector<std::size_t>> who;
  for (std::size_t r = 0; r < all.size(); ++r) {
    if (all[r].empty()) continue;
    const std::string m(reinterpret_cast<const char*>(all[r].data()), all[r].size());
    std::size_t k = 0;
    while (k < why.size() && why[k] != m) ++k;
    if (k == why.size()) {
      why.push_back(m);
      who.emplace_back();
    }
    who[k].push_back(r);
  }
  std::string report;
  for (std::size_t k = 0; k < why.size(); ++k) {
    if (k) report += "; ";
    report += who[k].size() > 1 ? "ranks " : "rank ";
    for (std::size_t q = 0; q < who[k].size(); ++q) report += (q ? ", " : "") + std::to_string(who[k][q]);
    report += ": " + why[k];
  }
  return report;
}

}  // namespace

void share_failure(const MpiContext& mpi, const std::string& error) {
  if (mpi.max(static_cast<std::int64_t>(error.empty() ? 0 : 1)) == 0) return;
  const auto* b = reinterpret_cast<const std::byte*>(error.data());
  const std::string report = joined(mpi.gather(std::vector<std::byte>(b, b + error.size()), 0));
  if (mpi.rank() != 0) throw RankFailure("another rank failed (rank 0 reports which and why)");
  throw RankFailure(report);
}

}  // namespace gf
