// The run's output folder, claimed before anything is built: a run never mixes its files with an
// earlier run's. A folder that holds anything is refused unless the run resumes (--resume continues
// the run whose folder it is) or --overwrite clears it, and --overwrite clears only a run's folder
// (one with a summary.json), so a mistyped --out never empties a folder of other files.
#pragma once

#include "app/cli.hpp"

namespace gf {

// Throws std::runtime_error naming the folder, what it holds and the fix; with --overwrite, empties it.
void claim_out_dir(const CliOptions& opt);

}  // namespace gf
