// ParaView output: one VTK XML PolyData (.vtp) file per frame, indexed by a .pvd collection that
// carries each frame's simulated time, so ParaView's time slider shows seconds, not frame numbers.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/grains.hpp"

namespace gf {

// Optional per-point arrays. Position, id, type (species in scene order, from 1), radius and
// diameter are always written.
struct FrameFields {
  bool velocity = true;          // "velocity" (3) and "speed"
  bool angular_velocity = true;  // "angular_velocity" (3)
  bool force = false;            // "force" (3): contact + wall force, as the integrator sees it
};

// A per-point array beyond the grains' own (a liquid's pressure): `values` holds one double per
// owned row. Written after the fields above, in the given order.
struct PointScalars {
  std::string_view name;
  const double* values = nullptr;
};

// A complete .vtp document for the owned rows [0, g.n_owned): ghosts are another rank's grains
// and would be drawn twice. Arrays use raw appended binary (UInt64 headers), which is exact
// (doubles round-trip bit for bit) and several times smaller and faster to load than ASCII.
std::string vtp_bytes(const Grains& g, const FrameFields& fields, std::span<const PointScalars> extra = {});

// Writes frames/frame_NNNNNN.vtp under an output folder and keeps frames.pvd beside it listing
// every frame written so far. Each frame is written atomically first and the .pvd rewritten
// atomically after it, so a run killed at any moment leaves a .pvd that opens in ParaView and
// lists only complete frames.
class FrameSeries {
 public:
  // Creates `out_dir/frames`. A run writing into an old run's folder replaces its .pvd with one
  // listing only this run's frames. Another series names its folder, .pvd and files after `name`
  // and `stem` (walls/walls_NNNNNN.vtp in walls.pvd) and its files' `extension` (.vtu for other
  // datasets); with `one_file` every entry lists the first file (a surface that does not move).
  explicit FrameSeries(std::filesystem::path out_dir, std::string name = "frames", std::string stem = "frame",
                       bool one_file = false, std::string extension = ".vtp");

  // Writes the next frame at simulated time `time` (s); returns the frame's path.
  // Throws std::invalid_argument for a non-finite time, std::runtime_error on I/O failure.
  std::filesystem::path write(const Grains& g, double time, const FrameFields& fields = {},
                              std::span<const PointScalars> extra = {});
  // Writes the next entry's document (made by `bytes()`, called only when a file is to be written).
  template <class Bytes>
  std::filesystem::path write_with(double time, Bytes&& bytes) {
    return add(time, [&] { return bytes(); });
  }

  std::size_t count() const { return frames_.size(); }
  std::vector<double> times() const;
  // Continues the frames of a resumed run: the index lists the frames at `times` (those written up
  // to the checkpoint, as frame_000000.vtp ...) and is rewritten atomically; later frames are
  // written again under the same names.
  void resume(const std::vector<double>& times);
  std::filesystem::path pvd_path() const { return dir_ / (name_ + ".pvd"); }

 private:
  std::filesystem::path add(double time, const std::function<std::string()>& bytes);
  std::string frame_name(std::size_t index) const;
  struct Entry {
    double time;
    std::string file;  // relative to dir_, '/'-separated as VTK expects
  };
  std::string pvd_bytes() const;

  std::filesystem::path dir_;
  std::string name_, stem_, extension_;
  bool one_file_ = false;
  std::vector<Entry> frames_;
};

}  // namespace gf
