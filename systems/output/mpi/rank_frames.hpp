// VTK frames of a run on several ranks, at the scene's frame_interval: each rank writes its owned
// grains as one piece, frames/frame_NNNNNN_rankRRRR.vtp (vtp_bytes, the one-rank frame's fields);
// rank 0 then writes frames/frame_NNNNNN.pvtp naming every piece and rewrites frames.pvd, the time
// index, in the run's folder. Every file is written atomically, the .pvtp after its pieces and the
// .pvd after the .pvtp, so the index never names a frame that is not whole on disk.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "engine/checkpoint_file.hpp"
#include "engine/grains.hpp"
#include "engine/mpi/mpi_context.hpp"
#include "systems/output/mpi/parallel_vtk.hpp"
#include "systems/output/vtk_frames.hpp"

namespace gf {

class RankFrames {
 public:
  // Rank 0 creates out/frames. Collective; RankFailure on every rank if it cannot.
  RankFrames(std::filesystem::path out, double interval, FrameFields fields, const MpiContext& mpi);
  // Writes a frame when the clock reached the next frame time (t = k interval, as on one rank).
  // Collective.
  void observe(const Grains& g, double t, double dt);
  // Writes the last state unless the latest frame shows it. Collective.
  void finish(const Grains& g, double t);
  std::size_t count() const { return frames_; }
  // The next frame time, the frames written and their times, in a checkpoint part and back.
  void save(CheckpointWriter& out) const;
  // Local: takes the state back (the frames after it are written again under the same names).
  void restore(const CheckpointReader& in);
  // Rank 0 rewrites frames.pvd listing the restored frames only. Collective.
  void rewrite_index();
  std::filesystem::path pvd_path() const { return out_ / "frames.pvd"; }
  // The file names of frame k, relative to out/frames.
  static std::string pvtp_name(std::size_t k);
  static std::string piece_name(std::size_t k, int rank);

 private:
  void write(const Grains& g, double t);
  std::filesystem::path out_;
  double interval_;
  FrameFields fields_;
  const MpiContext* mpi_;
  std::vector<PvdEntry> index_;
  std::size_t frames_ = 0;
  double next_ = 0;
  double last_written_ = -1;
};

}  // namespace gf
