#include "systems/output/mpi/rank_frames.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "systems/output/sample_grid.hpp"
#include "engine/atomic_file.hpp"
#include "engine/mpi/rank_failure.hpp"

namespace gf {

RankFrames::RankFrames(std::filesystem::path out, double interval, FrameFields fields, const MpiContext& mpi)
    : out_(std::move(out)), interval_(interval), fields_(fields), mpi_(&mpi) {
  on_every_rank(mpi, [&] {
    if (mpi.rank() == 0) ensure_directory(out_ / "frames");
  });
}

std::string RankFrames::pvtp_name(std::size_t k) {
  char name[40];
  std::snprintf(name, sizeof name, "frame_%06zu.pvtp", k);
  return name;
}

std::string RankFrames::piece_name(std::size_t k, int rank) {
  char name[48];
  std::snprintf(name, sizeof name, "frame_%06zu_rank%04d.vtp", k, rank);
  return name;
}

void RankFrames::observe(const Grains& g, double t, double dt) {
  if (!sample_due(t, next_, dt)) return;
  while (sample_due(t, next_, dt)) next_ += interval_;
  write(g, t);
}

void RankFrames::finish(const Grains& g, double t) {
  if (t != last_written_) write(g, t);
}

void RankFrames::write(const Grains& g, double t) {
  const MpiContext& mpi = *mpi_;
  const std::filesystem::path dir = out_ / "frames";
  const std::string piece = vtp_bytes(g, fields_);
  on_every_rank(mpi, [&] {
    if (!std::isfinite(t)) throw std::invalid_argument("frame time must be finite");
    write_file_atomic(dir / piece_name(frames_, mpi.rank()), piece);
  });
  index_.push_back({t, "frames/" + pvtp_name(frames_)});
  on_every_rank(mpi, [&] {
    if (mpi.rank() != 0) return;
    std::vector<std::string> sources;
    for (int r = 0; r < mpi.size(); ++r) sources.push_back(piece_name(frames_, r));
    write_file_atomic(dir / pvtp_name(frames_), pvtp_bytes(piece, sources));
    write_file_atomic(pvd_path(), pvd_bytes(index_));
  });
  ++frames_;
  last_written_ = t;
}

void RankFrames::save(CheckpointWriter& out) const {
  std::vector<double> times;
  for (const PvdEntry& e : index_) times.push_back(e.time);
  out.value("rank_frames.next", next_);
  out.value("rank_frames.last_written", last_written_);
  out.vector("rank_frames.times", std::move(times));
}

void RankFrames::restore(const CheckpointReader& in) {
  next_ = in.value<double>("rank_frames.next");
  last_written_ = in.value<double>("rank_frames.last_written");
  std::vector<double> times;
  in.vector("rank_frames.times", times);
  index_.clear();
  for (const double t : times) index_.push_back({t, "frames/" + pvtp_name(index_.size())});
  frames_ = index_.size();
}

void RankFrames::rewrite_index() {
  on_every_rank(*mpi_, [&] {
    if (mpi_->rank() == 0) write_file_atomic(pvd_path(), pvd_bytes(index_));
  });
}

}  // namespace gf
