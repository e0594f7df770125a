// The index files of VTK frames written in pieces, one piece per rank: a parallel PolyData file
// (.pvtp) that names the pieces of one frame and declares their arrays, and the .pvd collection that
// gives each frame's simulated time to ParaView's time slider.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace gf {

// A .pvtp document for pieces laid out like `piece` (a .vtp document from vtp_bytes: its
// PointData and Points arrays, with their types, names and components, are declared as the
// PPointData and PPoints), naming `sources` (paths relative to the .pvtp) as its pieces.
// std::invalid_argument if `piece` has no Points array.
std::string pvtp_bytes(std::string_view piece, std::span<const std::string> sources);

struct PvdEntry {
  double time;       // s
  std::string file;  // relative to the .pvd, '/'-separated
};
// A .pvd collection listing the entries in order, times in shortest round-trip form.
std::string pvd_bytes(std::span<const PvdEntry> entries);

}  // namespace gf
