// [[analysis.repose]] of a body scene: the heaps whose angle of repose the run reports at its end
// (summary.json "repose"; systems/analysis/body_repose.hpp). Keys:
//   name      a label for summary.json (unique)
//   geometry  "heap" (a cone about a vertical axis through `centre`, one flank), "ridge" or "crater"
//             (two flanks either side of the crest or the bottom, along the horizontal `across`;
//             the heap a flat-bottomed hopper leaves around its outlet is a crater)
//   centre    [x, y, z] (m; heap only)      across  [x, y, z] (ridge and crater only)
//   column    m, the width of a column of horizontal distance (two to four grain sizes is usual)
//   rank      the surface of a column is its rank-th highest member top (default 3)
//   lower, upper   the part of a flank's height range fitted (defaults 0.15 and 0.85)
//   region    { lo = [x, y, z], hi = [x, y, z] } (m): only members whose centre lies in this box
#pragma once

#include <vector>

#include "engine/scene.hpp"
#include "systems/analysis/body_repose.hpp"

namespace gf {

// SceneError naming the key and the fix for a bad table; `up` is the unit vector against gravity.
std::vector<ReposeSpec> read_repose(const SceneNode& analysis, const V3<double>& up);

}  // namespace gf
