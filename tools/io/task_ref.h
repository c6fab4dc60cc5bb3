// How results name the task they ran on, and how readers find that task again. A record names
// its task by the path relative to the task set's parent, "<task set>/<file>" (e.g.
// "tasks/env042.yaml" for /usr/share/vb/tasks/env042.yaml or ~/vb/tasks/env042.yaml), plus the
// FNV-1a of the task file and its height image: the same on every machine, without the
// absolute paths of the one that ran it. Records written before this carry absolute paths; they
// are still read (the path is tried as it is).
#pragma once

#include <string>
#include <vector>

namespace vb::io {

// "<name of the task file's directory>/<file name>"; the file name alone when the file lies
// in the filesystem root. A relative task_file is made absolute (against the cwd) first.
std::string TaskSetPath(const std::string& task_file);

// Where to look for the task a record names (`recorded`: provenance.task_file), in order:
//  - an absolute recorded path (older records): that path, then the rest of the list for its
//    "<task set>/<file>";
//  - <tasks_dir>/<file name> when tasks_dir is given (the task set the trials ran on: a tool's
//    --tasks DIR, or vb's shipped tasks);
//  - <dir>/<recorded> for the record's own directory and each of its parents (results stored
//    beside their task set, e.g. docs/results/... in a checkout with tasks/).
// Never the current directory. Callers must check each candidate's task name and FNV-1a
// against the record: a file at a candidate path may be another version of the task.
std::vector<std::string> TaskFileCandidates(const std::string& recorded,
                                            const std::string& record_path,
                                            const std::string& tasks_dir);

}  // namespace vb::io
