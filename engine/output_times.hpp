// When a run writes its outputs: the [output] keys that DEM, body, liquid and coupled scenes share.
#pragma once

namespace gf {

class SceneNode;
struct FieldTable;

struct OutputTimes {
  double series_interval = 0;      // s, 0: no series
  double frame_interval = 0;       // s, 0: no frames
  double checkpoint_interval = 0;  // s, 0: none during the run
  bool checkpoint_keep_all = false;
  bool checkpoint_at_end = true;   // also when the run is interrupted
};

// Reads series_interval, frame_interval, checkpoint_interval, checkpoint_keep_all and
// checkpoint_at_end from an [output] table. An interval shorter than the time step dt is refused at
// its key: it would write every step (and with checkpoint_keep_all a file per step, without bound).
void read_output_times(const SceneNode& out, double dt, OutputTimes& o);
// The same through a section's key table (engine/field_table.hpp), which must hold those five keys:
// their ranges and defaults are the table's.
void read_output_times(const SceneNode& out, double dt, OutputTimes& o, const FieldTable& fields);

}  // namespace gf
