#include "systems/output/summary_json.hpp"

#include <nlohmann/json.hpp>

#include "engine/atomic_file.hpp"

namespace gf {

void write_summary_json(const std::filesystem::path& file, const nlohmann::json& doc) {
  // Invalid UTF-8 (a scene name from a Latin-1 file, say) is replaced rather than thrown on:
  // losing a whole run's summary over one byte in one string is the worse outcome.
  std::string text = doc.dump(2, ' ', false, nlohmann::json::error_handler_t::replace);
  text += '\n';
  write_file_atomic(file, text);
}

}  // namespace gf
