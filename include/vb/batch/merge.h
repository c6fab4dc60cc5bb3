// Merging the index rows of several shard directories of one matrix: each trial (matrix index)
// once, in matrix order. A trial present in several inputs is a harmless duplicate when its
// stable fields agree (everything but host, wall time and task path) and a conflict otherwise;
// a row made by another build than its shard claims is a conflict too. Pure; vb_report merge
// does the file work.
#pragma once

#include <string>
#include <vector>

#include "vb/batch/index.h"

namespace vb::batch {

struct MergeInput {
  std::string origin;          // e.g. the shard directory, for messages and file copying
  std::string git_commit;      // of the shard (batch.json)
  std::string vb_version;
  std::vector<TrialRow> rows;
};

struct MergedRow {
  TrialRow row;
  std::string origin;          // where the kept copy comes from (the first input holding it)
};

struct MergeResult {
  std::vector<MergedRow> rows;           // sorted by matrix_index
  size_t duplicates = 0;
  std::vector<std::string> conflicts;    // empty = the merge is valid
};

MergeResult MergeIndexes(const std::vector<MergeInput>& inputs);

}  // namespace vb::batch
