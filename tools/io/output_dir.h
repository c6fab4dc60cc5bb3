// The resumable output directory of vb_batch and vb_collect (docs/batch.md "Resume"): one lock
// per directory, temporaries of killed writers removed, and the result-changing settings fixed
// by the first run (a later run with other settings is refused instead of mixing results).
#pragma once

#include <string>

namespace vb::io {

// Creates DIR and DIR/WORK_SUBDIR, takes DIR/.lock (held until this process ends, even by
// kill -9), removes files of DIR/WORK_SUBDIR whose names contain ".tmp." (writers killed
// mid-write), and checks DIR/settings.txt against `settings` (writes it on first use). Returns
// the lock's file descriptor (close it in forked children). InputError naming --out when the
// directory cannot be made, is locked by another `tool`, or holds results of other settings.
int PrepareOutputDir(const std::string& dir, const std::string& work_subdir,
                     const std::string& settings, const std::string& tool);

}  // namespace vb::io
