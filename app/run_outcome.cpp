#include "app/run_outcome.hpp"

#include <cmath>
#include <cstdio>

namespace gf {

void say_resuming(std::string_view program, const std::filesystem::path& file, const Clock& clock,
                  const std::string& note) {
  std::fprintf(stderr, "%s: resuming from %s at step %lld (t = %.6g s)%s\n", std::string(program).c_str(),
               file.string().c_str(), static_cast<long long>(clock.step), clock.t, note.c_str());
}

nlohmann::json resumed_from_json(const std::filesystem::path& file, const Clock& clock) {
  return {{"checkpoint", file.string()}, {"step", clock.step}, {"time", clock.t}};
}

nlohmann::json row_json(const std::vector<std::string>& columns, const std::vector<double>& row) {
  nlohmann::json j;
  for (std::size_t c = 0; c < columns.size(); ++c)
    j[columns[c]] = std::isfinite(row[c]) ? nlohmann::json(row[c]) : nlohmann::json();
  return j;
}

void say_done(std::string_view program, const RunOutcome& r, double simulated, const std::string& rate) {
  const std::string p(program);
  std::fprintf(stderr, "%s: %s after %lld steps (%.4g s simulated) in %.1f s wall: %s\n", p.c_str(), r.status.c_str(),
               static_cast<long long>(r.steps), simulated, r.wall, rate.c_str());
  if (!r.failure.empty()) std::fprintf(stderr, "%s: error: %s\n", p.c_str(), r.failure.c_str());
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace gf
