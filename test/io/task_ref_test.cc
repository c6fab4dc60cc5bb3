// How records name their task (task set path) and where readers look for it again.
#include "io/task_ref.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace vb::io {
namespace {

using Paths = std::vector<std::string>;

TEST(TaskRefTest, TaskSetPathIsTheSetDirectoryAndFileName) {
  EXPECT_EQ(TaskSetPath("/usr/share/vb/tasks/env042.yaml"), "tasks/env042.yaml");
  EXPECT_EQ(TaskSetPath("/home/me/vb/tasks/env042.yaml"), "tasks/env042.yaml");
  EXPECT_EQ(TaskSetPath("/scratch/gen/../mine/w7.yaml"), "mine/w7.yaml");
  EXPECT_EQ(TaskSetPath("/w7.yaml"), "w7.yaml");
  // Relative: against the current directory, which here is some directory of the test run.
  const std::string rel = TaskSetPath("env042.yaml");
  EXPECT_EQ(rel.substr(rel.size() - 12), "/env042.yaml") << rel;
}

TEST(TaskRefTest, CandidatesAreTheTaskSetThenTheRecordsDirectoryAndItsParents) {
  EXPECT_EQ(TaskFileCandidates("tasks/env042.yaml", "/a/results/trials/x.json",
                               "/usr/share/vb/tasks"),
            (Paths{"/usr/share/vb/tasks/env042.yaml", "/a/results/trials/tasks/env042.yaml",
                   "/a/results/tasks/env042.yaml", "/a/tasks/env042.yaml",
                   "/tasks/env042.yaml"}));
  EXPECT_EQ(TaskFileCandidates("tasks/env042.yaml", "/r/x.json", ""),
            (Paths{"/r/tasks/env042.yaml", "/tasks/env042.yaml"}));
  EXPECT_TRUE(TaskFileCandidates("", "/r/x.json", "/t").empty());
}

TEST(TaskRefTest, OlderRecordsWithAbsolutePathsAreStillFound) {
  // The recorded path first; then, moved to another machine, as its task set path.
  EXPECT_EQ(TaskFileCandidates("/home/dev/vb/tasks/env042.yaml", "/r/x.json", "/t"),
            (Paths{"/home/dev/vb/tasks/env042.yaml", "/t/env042.yaml", "/r/tasks/env042.yaml",
                   "/tasks/env042.yaml"}));
}

TEST(TaskRefTest, NeverTheCurrentDirectory) {
  // A relative record path is made absolute, so its own directory is looked in, and nothing
  // is relative to wherever the tool happens to run.
  for (const std::string& c : TaskFileCandidates("tasks/env042.yaml", "/r/x.json", "/t")) {
    EXPECT_EQ(c.front(), '/') << c;
  }
}

}  // namespace
}  // namespace vb::io
