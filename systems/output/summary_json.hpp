// The one place a run writes summary.json (final metrics, per-system timings), so every run's
// summary has the same format and is replaced atomically: a reader or a killed run never sees
// half a document.
#pragma once

#include <filesystem>

#include <nlohmann/json_fwd.hpp>

namespace gf {

struct SeriesRow;

// Pretty-printed (indent 2) with a trailing newline. Throws std::runtime_error on I/O failure.
void write_summary_json(const std::filesystem::path& file, const nlohmann::json& doc);

// A number, or null where it is not finite (JSON has no NaN or infinity).
nlohmann::json number_or_null(double v);

// The summary's "final": a grain run's last series row (its mixing and pattern measures where the
// scene has them), the same from one process and from several ranks.
nlohmann::json final_row_json(const SeriesRow& row);

}  // namespace gf
