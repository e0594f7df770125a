// The one place a run writes summary.json (final metrics, per-system timings), so every run's
// summary has the same format and is replaced atomically: a reader or a killed run never sees
// half a document.
#pragma once

#include <filesystem>

#include <nlohmann/json_fwd.hpp>

namespace gf {

// Pretty-printed (indent 2) with a trailing newline. Throws std::runtime_error on I/O failure.
void write_summary_json(const std::filesystem::path& file, const nlohmann::json& doc);

}  // namespace gf
