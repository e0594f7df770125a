// Whole-file writes that are either fully done or not done at all, so a run killed at any moment
// (or a full disk) never leaves a truncated checkpoint, summary or frame index behind.
#pragma once

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string_view>

namespace gf {

// An output that could not be written: a full disk, a file-size limit, no permission. Every writer
// of run results throws it, so a run can stop with "free space, then resume" rather than a
// generic failure. what() names the file and the system's reason.
class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Writes `bytes` to `path.tmp`, fsyncs it, renames it over `path` (atomic on POSIX) and fsyncs the
// folder so the rename itself survives a crash. Readers see either the old file or the new one.
// Throws WriteError naming the path and the system's reason on any failure; the old
// `path`, if any, is then left untouched.
void write_file_atomic(const std::filesystem::path& path, std::string_view bytes);
// The same for a file made of several pieces written one after the other (no joined copy).
void write_file_atomic(const std::filesystem::path& path, std::span<const std::string_view> pieces);

// Creates `dir` and its parents if missing. Throws WriteError naming the folder if it
// cannot be created or exists as something other than a folder.
void ensure_directory(const std::filesystem::path& dir);

}  // namespace gf
