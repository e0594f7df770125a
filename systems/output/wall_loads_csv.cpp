#include "systems/output/wall_loads_csv.hpp"

#include <cmath>
#include <set>
#include <stdexcept>

namespace gf {

namespace {

constexpr std::size_t kPerWall = kWallLoadNumbers;
constexpr const char* kSuffix[kPerWall] = {".fx", ".fy", ".fz", ".tx", ".ty", ".tz", ".power"};

std::vector<std::string> load_csv_columns(const std::vector<std::string>& names) {
  std::vector<std::string> c{"time"};
  for (const std::string& n : wall_load_columns(names))
    for (const char* s : kSuffix) c.push_back(n + s);
  return c;
}

// The seven running numbers of one wall: force, moment, power.
void add_load(const WallLoad& l, double* out) {
  const double v[kPerWall] = {l.force.x, l.force.y, l.force.z, l.moment.x, l.moment.y, l.moment.z, l.power};
  for (std::size_t k = 0; k < kPerWall; ++k) out[k] += v[k];
}

}  // namespace

std::vector<std::string> wall_load_columns(const std::vector<std::string>& names) {
  std::vector<std::string> out;
  std::set<std::string> used;
  for (const std::string& name : names) {
    std::string n;
    for (const char ch : name) n += (ch == ',' || ch == '"' || ch == '\n' || ch == '\r') ? '_' : ch;
    if (n.empty()) n = "wall";
    std::string unique = n;
    for (int k = 2; used.count(unique) != 0; ++k) unique = n + "-" + std::to_string(k);
    used.insert(unique);
    out.push_back(unique);
  }
  return out;
}

WallLoadsCsv::WallLoadsCsv(std::filesystem::path file, std::vector<std::string> names, std::size_t analytic,
                           double resume_time)
    : analytic_(analytic),
      csv_(std::isfinite(resume_time) ? SeriesCsv::resume_through(file, load_csv_columns(names), resume_time)
                                      : SeriesCsv(file, load_csv_columns(names))),
      written_(names.size() * kPerWall, 0.0) {}

WallLoadsCsv::WallLoadsCsv(std::filesystem::path file, std::vector<std::string> names, std::size_t analytic,
                           KeepRows keep)
    : analytic_(analytic),
      csv_(SeriesCsv::resume(file, load_csv_columns(names), keep.rows)),
      written_(names.size() * kPerWall, 0.0) {}

void WallLoadsCsv::write(double t, const WallLoads* walls, const WallLoads* meshes) {
  const std::size_t nw = written_.size() / kPerWall;
  std::vector<double> sum(nw * kPerWall, 0.0), now(nw * kPerWall, 0.0);
  std::int64_t steps = 0;
  for (const WallLoads* l : {walls, meshes}) {
    if (l == nullptr) continue;
    steps = std::max(steps, l->steps);
    const std::size_t first = l == walls ? 0 : analytic_;
    const std::size_t count = l == walls ? analytic_ : nw - analytic_;
    for (std::size_t k = 0; k < std::min(count, l->now.size()); ++k) {
      if (k < l->sum.size()) add_load(l->sum[k], &sum[(first + k) * kPerWall]);
      add_load(l->now[k], &now[(first + k) * kPerWall]);
    }
  }
  const std::int64_t n = steps - written_steps_;
  std::vector<double> row{t};
  for (std::size_t k = 0; k < nw * kPerWall; ++k) {
    // The mean since the last row; with no step since, the latest evaluation (the start).
    const double v = n > 0 ? (sum[k] - written_[k]) / static_cast<double>(n) : now[k];
    // On the wall: the negatives of the force and moment on the grains; the power is the drive's.
    row.push_back(k % kPerWall == kPerWall - 1 ? v : -v);
  }
  csv_.append(row);
  written_ = std::move(sum);
  written_steps_ = steps;
}

void WallLoadsCsv::save(CheckpointWriter& out) const {
  out.vector("wall_loads_csv.written", written_);
  out.value("wall_loads_csv.written_steps", written_steps_);
}

void WallLoadsCsv::restore(const CheckpointReader& in) {
  if (!in.has("wall_loads_csv.written")) return;  // a checkpoint of an older build: the first row averages less
  std::vector<double> w;
  in.vector("wall_loads_csv.written", w);
  in.require(w.size() == written_.size(), "the walls' load sums", "resume with the scene that wrote the checkpoint");
  written_ = std::move(w);
  written_steps_ = in.value<std::int64_t>("wall_loads_csv.written_steps");
}

}  // namespace gf
