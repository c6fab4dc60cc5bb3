// The resume rule: skip only records made by this build on this task version; retry crashed
// and missing ones; report everything else as stale with what changed.
#include "vb/batch/resume.h"

#include <gtest/gtest.h>

namespace vb::batch {
namespace {

TrialRow Record(const std::string& status) {
  TrialRow r;
  r.status = status;
  r.task_fnv1a64 = "aaaa";
  r.git_commit = "c1";
  r.vb_version = "0.1.0";
  return r;
}

TEST(ResumeTest, MissingAndCrashedTrialsRun) {
  EXPECT_EQ(DecideResume(nullptr, "aaaa", "c1", "0.1.0").action, ResumeAction::kRun);
  const TrialRow crashed = Record("crashed");
  EXPECT_EQ(DecideResume(&crashed, "aaaa", "c1", "0.1.0").action, ResumeAction::kRun);
}

TEST(ResumeTest, FinishedRecordsOfThisBuildAreSkippedWhateverTheirStatus) {
  for (const char* s : {"success", "rollover", "stuck", "timeout", "sim_error", "error"}) {
    const TrialRow r = Record(s);
    EXPECT_EQ(DecideResume(&r, "aaaa", "c1", "0.1.0").action, ResumeAction::kSkip) << s;
  }
}

TEST(ResumeTest, ChangedTaskCommitOrVersionIsStaleWithTheReason) {
  const TrialRow r = Record("success");
  const ResumeDecision task = DecideResume(&r, "bbbb", "c1", "0.1.0");
  EXPECT_EQ(task.action, ResumeAction::kStale);
  EXPECT_EQ(task.reason, "task changed aaaa -> bbbb");
  const ResumeDecision build = DecideResume(&r, "aaaa", "c2", "0.2.0");
  EXPECT_EQ(build.action, ResumeAction::kStale);
  EXPECT_EQ(build.reason, "git commit c1 -> c2, vb version 0.1.0 -> 0.2.0");
  // An error record is deterministic for its inputs, but a new build may be able to run it.
  const TrialRow e = Record("error");
  EXPECT_EQ(DecideResume(&e, "aaaa", "c2", "0.1.0").action, ResumeAction::kStale);
}

}  // namespace
}  // namespace vb::batch
