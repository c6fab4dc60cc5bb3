#include "vb/batch/merge.h"

#include <map>

namespace vb::batch {
MergeResult MergeIndexes(const std::vector<MergeInput>& inputs) {
  MergeResult result;
  std::map<size_t, MergedRow> merged;
  for (const MergeInput& in : inputs) {
    for (const TrialRow& r : in.rows) {
      if (r.git_commit != in.git_commit || r.vb_version != in.vb_version) {
        result.conflicts.push_back(RowStem(r) + " in " + in.origin + " was made by build " +
                                   r.git_commit + " " + r.vb_version + ", the shard by " +
                                   in.git_commit + " " + in.vb_version);
      }
      auto it = merged.find(r.matrix_index);
      if (it == merged.end()) {
        merged.emplace(r.matrix_index, MergedRow{r, in.origin});
      } else if (it->second.row.task != r.task || it->second.row.pair != r.pair ||
                 it->second.row.seed != r.seed || it->second.row.vehicle != r.vehicle ||
                 it->second.row.system != r.system ||
                 it->second.row.perception != r.perception) {
        result.conflicts.push_back("matrix index " + std::to_string(r.matrix_index) + " is " +
                                   RowStem(it->second.row) + " in " + it->second.origin +
                                   " but " + RowStem(r) + " in " + in.origin);
      } else if (StableFields(it->second.row) == StableFields(r)) {
        ++result.duplicates;
      } else {
        result.conflicts.push_back(RowStem(r) + ": " + it->second.origin + " and " + in.origin +
                                   " hold different results");
      }
    }
  }
  for (auto& [index, m] : merged) result.rows.push_back(std::move(m));
  return result;
}

}  // namespace vb::batch
