#include "systems/periodic/periodic_checkpoint.hpp"

#include <algorithm>
#include <string>

namespace gf {


void save_periodic_images(CheckpointWriter& out, const PeriodicImages& im) {
  if (!im.box.any()) return;
  out.vector("periodic.owner", im.owner);
  out.vector("periodic.shift_x", im.sx);
  out.vector("periodic.shift_y", im.sy);
  out.vector("periodic.shift_z", im.sz);
}

void restore_periodic_images(const CheckpointReader& in, PeriodicImages& im, const Grains& g) {
  const bool stored = in.has("periodic.owner");
  if (stored != im.box.any())
    in.fail(stored ? "it was written with [periodic] faces, the scene now has none"
                   : "it was written without [periodic] faces, the scene now has them",
            "resume with the scene (and --set overrides) of the run that wrote the checkpoint");
  if (!stored) {
    in.require(g.n == g.n_owned, "ghost rows without periodic faces", kFixResumeOrStateFile);
    return;
  }
  in.vector("periodic.owner", im.owner);
  in.vector("periodic.shift_x", im.sx);
  in.vector("periodic.shift_y", im.sy);
  in.vector("periodic.shift_z", im.sz);
  const bool rows = std::all_of(im.owner.begin(), im.owner.end(), [&](std::uint32_t o) { return o < g.n_owned; });
  in.require(im.owner.size() == g.n - g.n_owned && im.sx.size() == im.owner.size() &&
                 im.sy.size() == im.owner.size() && im.sz.size() == im.owner.size() && rows,
             "periodic images", kFixResumeOrStateFile);
}

}  // namespace gf
