// Resume rule of a batch: what to do with a trial given the record already in the output
// directory (if any), the task's current hash and this binary's identity. Pure; tested in
// test/batch/resume_test.cc, used by vb_batch.
#pragma once

#include <string>

#include "vb/batch/index.h"

namespace vb::batch {

enum class ResumeAction {
  kRun,     // no usable record (none, unreadable, or `crashed`): run the trial
  kSkip,    // finished by this build on this task version: keep it
  kStale,   // finished, but by another build or on another task version: report, do not mix
};

struct ResumeDecision {
  ResumeAction action = ResumeAction::kRun;
  std::string reason;   // for kStale: what changed, old -> new
};

// `existing` is the record read from the directory, nullptr if there is none (or it could not be
// read).
ResumeDecision DecideResume(const TrialRow* existing, const std::string& task_fnv1a64,
                            const std::string& git_commit, const std::string& vb_version);

}  // namespace vb::batch
