// Strict loading of perception models (data/perception/<preset>.yaml, docs/perception.md).
#pragma once

#include <string>
#include <vector>

#include "io/result_io.h"
#include "vb/engine/runner/perception.h"

namespace vb::io {

// Reads a perception file; the preset name is the file's stem. Throws InputError naming the
// file, line and key of the first bad value.
runner::PerceptionParams LoadPerception(const std::string& path);

// "none" (ground truth, no file), a preset name of <data_dir>/perception/ (e.g. "moderate"), or
// a path to a perception file (contains '/' or ends in .yaml). `flag` names the option in
// messages.
runner::PerceptionParams ResolvePerception(const std::string& name_or_path,
                                           const std::string& data_dir,
                                           const std::string& flag = "--perception");

// The file ResolvePerception reads for a name or path other than "none".
std::string PerceptionFile(const std::string& name_or_path, const std::string& data_dir);

// Preset names available in a data directory: "none" and the stems of <dir>/perception/*.yaml.
std::vector<std::string> PerceptionNames(const std::string& data_dir);

// Records the perception preset and its file's hash in a result's provenance ("none": nothing).
void RecordPerception(const std::string& name, const std::string& file, Provenance* p);

}  // namespace vb::io
