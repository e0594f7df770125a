#include "app/rank_launch.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <vector>

namespace gf {

std::optional<int> launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const char* v = std::getenv(name);
    if (v == nullptr || *v == '\0') continue;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    if (*end == '\0' && n > 0 && n < 1000000000) return static_cast<int>(n);
  }
  return std::nullopt;
}

std::string hand_over_to_ranks(int argc, char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "cannot find this program's own path (/proc/self/exe: " + ec.message() + ")";
  const std::filesystem::path target = self.parent_path() / "grainflow_mpi";
  if (access(target.c_str(), X_OK) != 0)
    return target.string() + " is missing: it is built beside grainflow when Open MPI is installed (README)";
  std::vector<char*> args;
  std::string name = target.string();
  args.push_back(name.data());
  for (int k = 1; k < argc; ++k) args.push_back(argv[k]);
  args.push_back(nullptr);
  execv(target.c_str(), args.data());
  return "cannot start " + target.string() + ": " + std::strerror(errno);
}

}  // namespace gf
