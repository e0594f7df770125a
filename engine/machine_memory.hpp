// This machine's physical memory: the bound for what a scene may ask to allocate or read.
#pragma once

#include <atomic>
#include <cstddef>

#include <unistd.h>

namespace gf {

// A lower bound than the machine's memory, for a process that must stay small: the input fuzzer
// sets it so that a scene asking for 60 MB is refused as quickly as one asking for 60 GB. 0: none.
inline std::atomic<std::size_t>& memory_limit() {
  static std::atomic<std::size_t> bytes{0};
  return bytes;
}

// Bytes of physical memory (or memory_limit(), when set and smaller); 0 when the system does not say.
inline std::size_t machine_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  const std::size_t physical =
      pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) : 0;
  const std::size_t limit = memory_limit().load();
  return limit > 0 && (physical == 0 || limit < physical) ? limit : physical;
}

// Half of it (4 GiB when unknown): the bound for files whose contents become arrays (states,
// checkpoints) and for the liquid's lattice.
inline std::size_t half_of_memory() {
  const std::size_t m = machine_memory();
  return m ? m / 2 : std::size_t(1) << 32;
}

}  // namespace gf
