// A grain state as CSV: `id,type,diameter,x,y,z`, optionally followed by `vx,vy,vz` and then by
// `wx,wy,wz`, SI units (diameter and position in m, velocity in m/s, angular velocity in rad/s).
// The common starting state for benchmarks and cross-code comparisons (scenes/data/), so reading
// it is strict: anything that is not exactly that table is an error naming file, line and fix.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <stdexcept>
#include <vector>

namespace gf {

struct StateRow {
  std::int64_t id;
  std::int32_t type;  // range checked by the caller, which knows the scene's species
  double diameter;    // m
  std::array<double, 3> x;  // m
  int line;  // 1-based line in the file it came from (0 for rows that were not read from a file)
  std::array<double, 3> v{};  // m/s; zero when the file has no velocity columns
  std::array<double, 3> w{};  // rad/s; zero when the file has no angular-velocity columns
};

// "<file>:<line>: <problem>. Fix: <fix>" (no line for a file that cannot be opened).
class StateCsvError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Header exactly `id,type,diameter,x,y,z`, `...,vx,vy,vz` or `...,vx,vy,vz,wx,wy,wz`; fields may
// carry surrounding spaces, lines a trailing \r, and blank lines are skipped. Diameters must be
// finite and > 0, positions and velocities finite, ids unique.
std::vector<StateRow> read_state_csv(const std::filesystem::path& file);

// All twelve columns; numbers in shortest round-trip form, so read_state_csv gives back the same bits.
// Written to a temporary beside the target and renamed over it, so a crash never leaves half a file.
void write_state_csv(const std::filesystem::path& file, std::span<const StateRow> rows);

}  // namespace gf
