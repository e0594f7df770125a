// The commit the program was built from (`git describe --always --dirty`, "unknown" outside a git clone),
// written at every build by tools/commit_id.cmake: summary.json records it beside the version.
#pragma once

namespace gf {

const char* build_commit();

}  // namespace gf
