// Where the tools find their data: VB_DATA_DIR, else share/vb/data next to the executable (the
// build tree mirrors the install layout with symlinks), and a clear error for an unusable one.
#include "io/data_dir.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

class DataDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* v = std::getenv("VB_DATA_DIR");
    had_ = v != nullptr;
    if (had_) saved_ = v;
    ::unsetenv("VB_DATA_DIR");
  }
  void TearDown() override {
    if (had_) ::setenv("VB_DATA_DIR", saved_.c_str(), 1);
    else ::unsetenv("VB_DATA_DIR");
  }
  bool had_ = false;
  std::string saved_;
};

TEST_F(DataDirTest, NextToTheExecutableByDefault) {
  // This test program is build/test/<name>: share/vb is build/share/vb, links to the source.
  EXPECT_EQ(fs::path(ShareDir()), fs::path(ExecutableDir()).parent_path() / "share" / "vb");
  const std::string dir = DataDir();
  EXPECT_EQ(dir, ShareDir() + "/data");
  EXPECT_TRUE(fs::exists(fs::path(dir) / "vehicles" / "hmmwv.yaml"));
  EXPECT_TRUE(fs::exists(fs::path(TasksDir()) / "env042.yaml"));
  EXPECT_TRUE(fs::exists(fs::path(WebDir()) / "index.html"));
  EXPECT_EQ(fs::canonical(dir), fs::canonical(VB_SOURCE_DIR "/data"));
}

TEST_F(DataDirTest, EnvironmentOverrides) {
  ::setenv("VB_DATA_DIR", VB_SOURCE_DIR "/data", 1);
  EXPECT_EQ(DataDir(), VB_SOURCE_DIR "/data");
}

TEST_F(DataDirTest, EmptyOrMissingDirectorySaysWhereItLookedAndWhatToDo) {
  const fs::path empty = fs::temp_directory_path() / ("vb_data_dir_" + std::to_string(::getpid()));
  fs::create_directories(empty / "vehicles");
  for (const fs::path& dir : {empty, empty / "missing"}) {
    ::setenv("VB_DATA_DIR", dir.c_str(), 1);
    try {
      DataDir();
      FAIL() << "no error for " << dir;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(dir.string()), std::string::npos) << what;
      EXPECT_NE(what.find("from the environment variable VB_DATA_DIR"), std::string::npos) << what;
      EXPECT_NE(what.find("VB_DATA_DIR=DIR"), std::string::npos) << what;
    }
  }
  fs::remove_all(empty);
}

}  // namespace
}  // namespace vb::io
