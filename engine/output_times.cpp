#include "engine/output_times.hpp"

#include "engine/scene.hpp"

namespace gf {

namespace {

const Field kOutputTimes[] = {
    {"series_interval", "s", range::time_span, "0, or ≥ `run.dt`", 0.0, "", "one `series.csv` row per interval; 0: no series"},
    {"frame_interval", "s", range::time_span, "0, or ≥ `run.dt`", 0.0, "", "one frame per interval; 0: no frames"},
    {"checkpoint_interval", "s", range::time_span, "0, or ≥ `run.dt`", 0.0, "",
     "a checkpoint every interval; 0: only at the end"},
    {"checkpoint_keep_all", "", kAnyNumber, "true, false", kNoDefault, "false",
     "keep every checkpoint as `checkpoint_<step>.gfc`, not only the last"},
    {"checkpoint_at_end", "", kAnyNumber, "true, false", kNoDefault, "true",
     "write a checkpoint at the end (also when interrupted)"},
};

}  // namespace

const FieldTable kOutputTimesFields{"[output] times", "", kOutputTimes};

void read_output_times(const SceneNode& out, double dt, OutputTimes& o) {
  const FieldTable& t = kOutputTimesFields;
  o.series_interval = read_number(out, t.field("series_interval"));
  o.frame_interval = read_number(out, t.field("frame_interval"));
  o.checkpoint_interval = read_number(out, t.field("checkpoint_interval"));
  o.checkpoint_keep_all = read_bool(out, t.field("checkpoint_keep_all"));
  o.checkpoint_at_end = read_bool(out, t.field("checkpoint_at_end"));
  if (o.series_interval > 0 && o.series_interval < dt)
    out.fail("series_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no series");
  if (o.frame_interval > 0 && o.frame_interval < dt)
    out.fail("frame_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no frames");
  if (o.checkpoint_interval > 0 && o.checkpoint_interval < dt)
    out.fail("checkpoint_interval", "shorter than the time step",
             "use a multiple of run.dt, or 0 for a checkpoint only at the end");
}

}  // namespace gf
