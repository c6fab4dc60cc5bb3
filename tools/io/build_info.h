// The git commit this binary was built from, determined at build time (not at CMake configure
// time, which goes stale): cmake/vb_build_info.cmake regenerates its definition on every build
// and rewrites it only when HEAD (or the tracked-files-dirty flag) changed.
#pragma once

namespace vb::io {

// Short commit hash, "<hash>-dirty" if tracked files differed from HEAD, or "unknown".
const char* BuildGitCommit();

}  // namespace vb::io
