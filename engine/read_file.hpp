// Reading an input file whole, safely: only a regular file (not a folder, device or pipe, which could
// block or never end), only up to a size bound (so a wrong path cannot exhaust memory).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

namespace gf {

struct FileProblem {
  std::string problem, fix;  // for the caller's message, which names the file and the key
};

// Reads `file` into `out`. Returns false with `why` filled when the path is empty, missing,
// unreadable, not a regular file, or larger than max_bytes.
bool read_regular_file(const std::filesystem::path& file, std::size_t max_bytes, std::string& out, FileProblem& why);

}  // namespace gf
