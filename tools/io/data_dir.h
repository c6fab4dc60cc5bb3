// Where the vb tools find their shared files (vehicles, soils, perception presets, tasks, the
// viewer's page): relative to the running executable, never through a path compiled in from the
// source or build tree. An install puts the tools in <prefix>/bin and the files in
// <prefix>/share/vb/{data,tasks,web}; the build tree mirrors that layout with relative symlinks
// (build/share/vb/data -> ../../../data, ...: cmake/vb_install.cmake), so built and installed
// tools look alike.
// Environment overrides: VB_DATA_DIR (data), VB_WEB_DIR (the viewer's static files).
#pragma once

#include <cstddef>
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

// Longest vehicle, soil or perception preset name: it becomes part of output file names.
constexpr size_t kMaxDataNameLength = 64;

// The file of a named parameter set: DATA_DIR/KIND/NAME.yaml (KIND: "vehicles", "soils",
// "perception"). The one name rule of every tool for such names (flags, gym requests, names read
// back from records): NAME must be a file-name component (vb::FileNameComponentProblem, at most
// kMaxDataNameLength characters) and one of YamlNamesIn(DATA_DIR/KIND), so that it is never a
// path ("../x", "/etc/y") and every output file named after it stays where it belongs. Throws
// InputError(file, 0, key, ...) listing the valid names.
std::string ListedDataFile(const std::string& data_dir, const std::string& kind,
                           const std::string& name, const std::string& key,
                           const std::string& file = "");

// The task set that ships with vb: <ShareDir()>/tasks (may not exist; not checked).
std::string TasksDir();

// The viewer's static files: $VB_WEB_DIR when set and non-empty, else <ShareDir()>/web/viewer.
std::string WebDir();

}  // namespace vb::io
