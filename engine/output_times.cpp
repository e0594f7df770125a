#include "engine/output_times.hpp"

#include <limits>

#include "engine/field_table.hpp"
#include "engine/scene.hpp"

namespace gf {

namespace {

constexpr Range kNonNegative{0, std::numeric_limits<double>::infinity(), false, true};

// The five keys' ranges and defaults, for the sections that have no table of their own yet.
const Field kTimes[] = {
    {"series_interval", "s", kNonNegative, "", 0.0, "", ""},
    {"frame_interval", "s", kNonNegative, "", 0.0, "", ""},
    {"checkpoint_interval", "s", kNonNegative, "", 0.0, "", ""},
    {"checkpoint_keep_all", "", kAnyNumber, "", kNoDefault, "false", ""},
    {"checkpoint_at_end", "", kAnyNumber, "", kNoDefault, "true", ""},
};
const FieldTable kTimesFields{"[output]", "", kTimes};

}  // namespace

void read_output_times(const SceneNode& out, double dt, OutputTimes& o) { read_output_times(out, dt, o, kTimesFields); }

void read_output_times(const SceneNode& out, double dt, OutputTimes& o, const FieldTable& fields) {
  o.series_interval = read_number(out, fields.field("series_interval"));
  o.frame_interval = read_number(out, fields.field("frame_interval"));
  o.checkpoint_interval = read_number(out, fields.field("checkpoint_interval"));
  o.checkpoint_keep_all = read_bool(out, fields.field("checkpoint_keep_all"));
  o.checkpoint_at_end = read_bool(out, fields.field("checkpoint_at_end"));
  if (o.series_interval > 0 && o.series_interval < dt)
    out.fail("series_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no series");
  if (o.frame_interval > 0 && o.frame_interval < dt)
    out.fail("frame_interval", "shorter than the time step", "use a multiple of run.dt, or 0 for no frames");
  if (o.checkpoint_interval > 0 && o.checkpoint_interval < dt)
    out.fail("checkpoint_interval", "shorter than the time step",
             "use a multiple of run.dt, or 0 for a checkpoint only at the end");
}

}  // namespace gf
