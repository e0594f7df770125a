#include "app/out_dir.hpp"

#include <algorithm>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "engine/user_text.hpp"

namespace gf {

namespace {

namespace fs = std::filesystem;

// Up to four entries by name ("summary.json, series.csv, frames/ and 5 more"), for the message.
std::string some_entries(const std::vector<fs::directory_entry>& entries) {
  std::vector<std::string> names;
  for (const auto& e : entries) names.push_back(clipped(e.path().filename().string(), 40) + (e.is_directory() ? "/" : ""));
  std::sort(names.begin(), names.end());
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < 4; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > 4) out += " and " + std::to_string(names.size() - 4) + " more";
  return out;
}

}  // namespace

void claim_out_dir(const CliOptions& opt) {
  const fs::path dir = opt.out_dir();
  const std::string shown = quoted(dir.string(), 80);
  std::error_code ec;
  if (!fs::exists(dir, ec)) return;
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error("the output folder " + shown + " is a file. Fix: give --out a folder's path");
  if (opt.resume) return;  // the resumed run's own folder: its files go on
  std::vector<fs::directory_entry> entries;
  for (const auto& e : fs::directory_iterator(dir, ec)) entries.push_back(e);
  if (ec) throw std::runtime_error("cannot list the output folder " + shown + ": " + ec.message() + ". Fix: give another --out");
  if (entries.empty()) return;
  if (!opt.overwrite)
    throw std::runtime_error("the output folder " + shown + " already holds " + some_entries(entries) +
                             ": a new run would leave them beside its own files. Fix: add --overwrite to clear it, "
                             "--resume " + (dir / "checkpoints" / "checkpoint.gfc").string() +
                             " to continue its run, or give another --out");
  if (!fs::exists(dir / "summary.json", ec))
    throw std::runtime_error("the output folder " + shown + " holds " + some_entries(entries) +
                             " but no summary.json, so it is not a grainflow run's folder, and --overwrite clears only "
                             "those. Fix: give another --out, or empty the folder yourself");
  for (const auto& e : entries) {
    fs::remove_all(e.path(), ec);
    if (ec)
      throw std::runtime_error("--overwrite could not remove " + quoted(e.path().string(), 80) + ": " + ec.message() +
                               ". Fix: check the folder's permissions, or give another --out");
  }
}

}  // namespace gf
