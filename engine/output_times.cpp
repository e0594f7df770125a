#include "engine/output_times.hpp"

#include "engine/scene.hpp"

namespace gf {

void read_output_times(const SceneNode& out, double dt, OutputTimes& o) {
  o.series_interval = out.get_double("series_interval", 0.0, Range::non_negative());
  o.frame_interval = out.get_double("frame_interval", 0.0, Range::non_negative());
  o.checkpoint_interval = out.get_double("checkpoint_interval", 0.0, Range::non_negative());
  o.checkpoint_keep_all = out.get_bool("checkpoint_keep_all", false);
  o.checkpoint_at_end = out.get_bool("checkpoint_at_end", true);
  if (o.series_interval > 0 && o.series_interval < dt)
    out.fail("series_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no series");
  if (o.frame_interval > 0 && o.frame_interval < dt)
    out.fail("frame_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no frames");
  if (o.checkpoint_interval > 0 && o.checkpoint_interval < dt)
    out.fail("checkpoint_interval", "shorter than the time step",
             "use a multiple of run.dt, or 0 for a checkpoint only at the end");
}

}  // namespace gf
