#include "vb/batch/resume.h"

namespace vb::batch {

ResumeDecision DecideResume(const TrialRow* existing, const std::string& task_fnv1a64,
                            const std::string& git_commit, const std::string& vb_version) {
  ResumeDecision d;
  // A crashed worker says nothing about the trial (it may have been killed by the machine):
  // retry it.
  if (existing == nullptr || existing->status == "crashed") return d;
  auto changed = [&](const char* what, const std::string& old_value,
                     const std::string& new_value) {
    if (old_value == new_value) return;
    d.reason += std::string(d.reason.empty() ? "" : ", ") + what + " " + old_value + " -> " +
                new_value;
  };
  changed("task changed", existing->task_fnv1a64, task_fnv1a64);
  changed("git commit", existing->git_commit, git_commit);
  changed("vb version", existing->vb_version, vb_version);
  d.action = d.reason.empty() ? ResumeAction::kSkip : ResumeAction::kStale;
  return d;
}

}  // namespace vb::batch
