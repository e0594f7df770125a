#include "app/run_outcome.hpp"

#include <cmath>
#include <cstdio>

namespace gf {

void say_resuming(const CheckpointReader& from, const Clock& clock) {
  std::fprintf(stderr, "grainflow: resuming from %s at step %lld (t = %.6g s)\n", from.file().string().c_str(),
               static_cast<long long>(clock.step), clock.t);
}

nlohmann::json resumed_from_json(const CheckpointReader& from, const Clock& clock) {
  return {{"checkpoint", from.file().string()}, {"step", clock.step}, {"time", clock.t}};
}

nlohmann::json row_json(const std::vector<std::string>& columns, const std::vector<double>& row) {
  nlohmann::json j;
  for (std::size_t c = 0; c < columns.size(); ++c)
    j[columns[c]] = std::isfinite(row[c]) ? nlohmann::json(row[c]) : nlohmann::json();
  return j;
}

void say_done(const RunOutcome& r, double simulated, const std::string& rate) {
  std::fprintf(stderr, "grainflow: %s after %lld steps (%.4g s simulated) in %.1f s wall%s\n", r.status.c_str(),
               static_cast<long long>(r.steps), simulated, r.wall, rate.c_str());
  if (!r.failure.empty()) std::fprintf(stderr, "grainflow: error: %s\n", r.failure.c_str());
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace gf
