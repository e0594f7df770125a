#include "app/run_summary.hpp"

#include <tbb/global_control.h>

#include "app/build_commit.hpp"
#include "engine/schedule.hpp"

namespace gf {

void summary_opening(nlohmann::json& summary, const CliOptions& opt, std::string_view model, RunCounts at_start,
                     int ranks, std::size_t threads) {
  summary["program"] = "grainflow";
  summary["version"] = GRAINFLOW_VERSION;
  summary["commit"] = build_commit();
  summary["model"] = std::string(model);
  summary["scene"] = opt.scene.string();
  summary["overrides"] = opt.overrides;
  summary["ranks"] = ranks;
  summary["threads"] = threads;
  summary["counts"] = {{"grains_at_start", at_start.grains},
                       {"grains_at_end", at_start.grains},
                       {"nodes_at_start", at_start.nodes},
                       {"nodes_at_end", at_start.nodes}};
}

void summary_counts_at_end(nlohmann::json& summary, RunCounts at_end) {
  summary["counts"]["grains_at_end"] = at_end.grains;
  summary["counts"]["nodes_at_end"] = at_end.nodes;
}

std::size_t threads_in_use() {
  return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
}

nlohmann::json timings_json(const std::vector<const Schedule*>& schedules) {
  double total = 0.0;
  for (const Schedule* s : schedules)
    for (const SystemTiming& t : s->timings()) total += t.seconds;
  nlohmann::json out = nlohmann::json::array();
  for (const Schedule* s : schedules)
    for (const SystemTiming& t : s->timings())
      out.push_back({{"system", t.name},
                     {"seconds", t.seconds},
                     {"calls", t.calls},
                     {"fraction", total > 0 ? t.seconds / total : 0.0}});
  return out;
}

}  // namespace gf
