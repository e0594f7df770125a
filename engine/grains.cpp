#include "engine/grains.hpp"

#include <tbb/parallel_for_each.h>

#include <functional>
#include <vector>

namespace gf {

void Grains::permute(std::span<const std::uint32_t> perm) {
  // Columns are independent, so they are permuted concurrently; each thread reuses its scratch.
  std::vector<std::function<void()>> jobs;
  jobs.reserve(40);
  for_each_core_column([&](auto& col) { jobs.emplace_back([&col, perm] { col.permute(perm); }); });
  tbb::parallel_for_each(jobs.begin(), jobs.end(), [](const std::function<void()>& job) { job(); });
  extras.permute(perm);
}

std::size_t Grains::bytes() {
  std::size_t b = 0;
  for_each_core_column([&b](auto& col) { b += col.bytes(); });
  return b + extras.bytes();
}

}  // namespace gf
