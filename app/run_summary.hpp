// The part of summary.json that every model writes alike, so one reader serves all five: what ran
// (program version, model, scene, overrides, ranks and threads), the counts of grains and liquid nodes
// at the start and the end, and the time per system with its fraction of the step.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli.hpp"

namespace gf {

class Schedule;

// Grains (spheres, or composite bodies) and liquid nodes.
struct RunCounts {
  std::int64_t grains = 0;
  std::int64_t nodes = 0;
};

// "program", "version", "model" (spheres, bodies, liquid, coupled), "scene", "overrides", "ranks",
// "threads" (per rank) and "counts" with the start's counts (and the end's, equal, until
// summary_counts_at_end).
void summary_opening(nlohmann::json& summary, const CliOptions& opt, std::string_view model, RunCounts at_start,
                     int ranks, std::size_t threads);
void summary_counts_at_end(nlohmann::json& summary, RunCounts at_end);

// The worker threads oneTBB may use (--threads, or every core).
std::size_t threads_in_use();

// One entry per system of the schedules, in their order: name, seconds, calls and the fraction of
// the schedules' summed time.
nlohmann::json timings_json(const std::vector<const Schedule*>& schedules);

}  // namespace gf
