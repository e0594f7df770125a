// This machine's physical memory: the bound for what a scene may ask to allocate or read.
#pragma once

#include <cstddef>

#include <unistd.h>

namespace gf {

// Bytes of physical memory; 0 when the system does not say.
inline std::size_t machine_memory() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? static_cast<std::size_t>(pages) * static_cast<std::size_t>(page) : 0;
}

// Half of it (4 GiB when unknown): the bound for files whose contents become arrays (states,
// checkpoints) and for the liquid's lattice.
inline std::size_t half_of_memory() {
  const std::size_t m = machine_memory();
  return m ? m / 2 : std::size_t(1) << 32;
}

}  // namespace gf
