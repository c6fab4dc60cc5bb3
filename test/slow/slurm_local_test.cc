// The local Slurm test (scripts/slurm_local_test.sh) as a CTest test with the `slow` label: it
// needs root, the Debian slurm-wlm and munge packages (installed by the script if missing) and
// starts private Slurm daemons, so CI (-LE slow) does not run it. Run it with
//   ctest --test-dir build -L slow -R Slurm --output-on-failure
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include <gtest/gtest.h>

TEST(SlurmLocalTest, TwoShardArrayAndMergeEqualALocalRun) {
  if (::geteuid() != 0) GTEST_SKIP() << "needs root to start slurmctld/slurmd/munged";
  const std::string cmd = std::string(VB_SOURCE_DIR "/scripts/slurm_local_test.sh ") +
                          VB_BIN_DIR "/.. 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), p)) > 0) out.append(buf, n);
  const int status = pclose(p);
  ASSERT_TRUE(WIFEXITED(status)) << out;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  EXPECT_NE(out.find("slurm test: PASS"), std::string::npos) << out;
}
