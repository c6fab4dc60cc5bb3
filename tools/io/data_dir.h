// Where the vb tools find their shared files (vehicles, soils, perception presets, tasks, the
// viewer's page): relative to the running executable, never through a path compiled in from the
// source or build tree. An install puts the tools in <prefix>/bin and the files in
// <prefix>/share/vb/{data,tasks,web}; the build tree mirrors that layout with symlinks
// (build/share/vb/* -> the source tree), so built and installed tools look alike.
// Environment overrides: VB_DATA_DIR (data), VB_WEB_DIR (the viewer's static files).
#pragma once

#include <string>
#include <vector>

namespace vb::io {

// Directory of the running executable (/proc/self/exe, symlinks resolved); "" if unknown.
std::string ExecutableDir();

// <executable dir>/../share/vb, normalised ("" if the executable's location is unknown).
std::string ShareDir();

// The data directory: $VB_DATA_DIR when set and non-empty, else <ShareDir()>/data. Checked: it
// must hold a readable vehicles/ directory with at least one .yaml file; otherwise throws
// InputError saying where it looked (and why there) and how to point vb at the data.
std::string DataDir();

// The names (file stems) of the regular .yaml files in `dir`, sorted: what the tools list as the
// valid vehicles, soils and perception presets. None when `dir` is missing or cannot be read.
std::vector<std::string> YamlNamesIn(const std::string& dir);

// The task set that ships with vb: <ShareDir()>/tasks (may not exist; not checked).
std::string TasksDir();

// The viewer's static files: $VB_WEB_DIR when set and non-empty, else <ShareDir()>/web/viewer.
std::string WebDir();

}  // namespace vb::io
