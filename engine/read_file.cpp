#include "engine/read_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <system_error>

namespace gf {

namespace {
std::string size_text(std::uintmax_t bytes) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g MB", static_cast<double>(bytes) / 1e6);
  return buf;
}
}  // namespace

bool read_regular_file(const std::filesystem::path& file, std::size_t max_bytes, std::string& out, FileProblem& why) {
  namespace fs = std::filesystem;
  if (file.empty() || file.filename().empty()) {
    why = {"no file name is given", "give the path of a file"};
    return false;
  }
  std::error_code ec;
  const fs::file_status st = fs::status(file, ec);
  if (ec || !fs::exists(st)) {
    why = {"the file does not exist", "check the path"};
    return false;
  }
  if (!fs::is_regular_file(st)) {
    why = {fs::is_directory(st) ? "this is a folder, not a file" : "this is not a regular file (a device or a pipe)",
           "give the path of a regular file"};
    return false;
  }
  const std::uintmax_t size = fs::file_size(file, ec);
  if (!ec && size > max_bytes) {
    why = {"the file is " + size_text(size) + ", above the " + size_text(max_bytes) + " this input may have",
           "check that this is the intended file"};
    return false;
  }
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) {
    why = {std::string("cannot open it (") + std::strerror(errno) + ")", "check that the file is readable"};
    return false;
  }
  out.clear();
  char buf[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) {
    if (out.size() + n > max_bytes) {  // it grew while being read
      why = {"the file is larger than the " + size_text(max_bytes) + " this input may have",
             "check that this is the intended file"};
      return false;
    }
    out.append(buf, n);
  }
  if (std::ferror(f.get())) {
    why = {"read error", "check that the file is readable"};
    return false;
  }
  return true;
}

}  // namespace gf
