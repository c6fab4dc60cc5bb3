// Names that become part of output file names (task, vehicle and system names in
// <task>_p<K>_s<seed>_<vehicle>_<system>.json): one rule, checked wherever such a name enters
// (task loader, tool flags, index rows), so nothing written under an output directory can leave
// it or hide in it, whatever the inputs say.
#pragma once

#include <cstddef>
#include <string>

namespace vb {

// Why `name` cannot be a file-name component, or "" if it can: 1 to max_length characters of
// [A-Za-z0-9_.-], not starting with '.' or '-' (no "..", no hidden files, no options), ASCII
// (so it is valid UTF-8 in every JSON record and CSV row).
std::string FileNameComponentProblem(const std::string& name, size_t max_length);

}  // namespace vb
