// walls.csv: each wall's and mesh wall's load per series row, as the mean over the full steps since
// the previous row (the first row, at the start, is the priming evaluation's): the force on the wall
// (N), the torque on it about its current rotation point (N m) and the power its drive supplies (W;
// positive when the wall drives the grains), walls.hpp. Seven columns per wall, "<name>.fx", ".fy",
// ".fz", ".tx", ".ty", ".tz", ".power", after "time"; the analytic walls in scene order (a box's six
// faces and a drum's mantle and ends apart), then the meshes.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "systems/output/series_csv.hpp"
#include "systems/walls/walls.hpp"

namespace gf {

// The columns for walls named `names` (in order): names made unique ("-2", "-3" after a repeat) and
// free of the characters a CSV header cannot hold unquoted.
std::vector<std::string> wall_load_columns(const std::vector<std::string>& names);

class WallLoadsCsv {
 public:
  // A new file, or with resume_time finite the rows of an existing one up to that time kept. `names`:
  // the first `analytic` are the analytic walls', the rest the meshes'.
  WallLoadsCsv(std::filesystem::path file, std::vector<std::string> names, std::size_t analytic, double resume_time);
  // The rows of an existing file up to `keep_rows` kept (a run whose series counts its rows).
  struct KeepRows {
    std::size_t rows = 0;
  };
  WallLoadsCsv(std::filesystem::path file, std::vector<std::string> names, std::size_t analytic, KeepRows keep);
  // One row at time t from the analytic walls' and the meshes' loads (either may be absent).
  void write(double t, const WallLoads* walls, const WallLoads* meshes);
  // The running sums at the last row (the loads' own sums are checkpointed with the walls), so that
  // a resumed run's first row averages over its whole interval.
  void save(CheckpointWriter& out) const;
  void restore(const CheckpointReader& in);

 private:
  std::size_t analytic_;
  SeriesCsv csv_;
  std::vector<double> written_;  // per wall: force, moment, power summed up to the last row (7 numbers)
  std::int64_t written_steps_ = 0;
};

}  // namespace gf
