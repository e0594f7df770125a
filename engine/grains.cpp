#include "engine/grains.hpp"

#include <tbb/parallel_for_each.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <string>
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

std::int64_t Grains::queue_insert(GrainRow row) {
  row.id = next_id++;
  pending.insert.push_back(row);
  return row.id;
}

std::vector<std::int64_t> Grains::apply_pending() {
  std::vector<std::int64_t> gone = pending.remove;
  std::sort(gone.begin(), gone.end());
  gone.erase(std::unique(gone.begin(), gone.end()), gone.end());
  std::vector<std::int64_t> new_row(n, -1);
  std::vector<std::uint32_t> keep;
  keep.reserve(n_owned);
  std::size_t found = 0;
  for (std::size_t r = 0; r < n_owned; ++r) {
    if (std::binary_search(gone.begin(), gone.end(), pid.id[r])) {
      ++found;
      continue;
    }
    new_row[r] = static_cast<std::int64_t>(keep.size());
    keep.push_back(static_cast<std::uint32_t>(r));
  }
  if (found != gone.size()) {
    std::string missing;
    for (std::int64_t id : gone) {
      bool present = false;
      for (std::size_t r = 0; r < n_owned && !present; ++r) present = pid.id[r] == id;
      if (!present) missing += (missing.empty() ? "" : ", ") + std::to_string(id);
    }
    throw std::invalid_argument("grains queued for removal are not in the table: id " + missing);
  }
  permute(keep);
  const std::size_t kept = keep.size();
  resize(kept + pending.insert.size());
  for (std::size_t k = 0; k < pending.insert.size(); ++k) {
    const GrainRow& g = pending.insert[k];
    const std::size_t r = kept + k;
    pos.x[r] = g.x[0], pos.y[r] = g.x[1], pos.z[r] = g.x[2];
    vel.x[r] = g.v[0], vel.y[r] = g.v[1], vel.z[r] = g.v[2];
    if (spin) omega.x[r] = g.w[0], omega.y[r] = g.w[1], omega.z[r] = g.w[2];  // no spin columns without rotation
    radius.r[r] = g.radius;
    mass.m[r] = g.mass;
    mass.inv_m[r] = 1.0 / g.mass;
    mass.inv_inertia[r] = g.inv_inertia;
    species.type[r] = g.type;
    pid.id[r] = g.id;
  }
  pending = {};
  return new_row;
}

std::size_t Grains::bytes() {
  std::size_t b = 0;
  for_each_core_column([&b](auto& col) { b += col.bytes(); });
  return b + extras.bytes();
}

}  // namespace gf
