// Tests for tools/io/yaml_strict.cc: number formatting that round-trips, and atomic writes.
#include "io/yaml_strict.h"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

TEST(FormatDoubleTest, ReadsBackBitExact) {
  std::mt19937_64 rng(20240611);  // fixed seed: deterministic test
  std::uniform_real_distribution<double> uniform(-200.0, 200.0);
  for (int i = 0; i < 10000; ++i) {
    // Mix ordinary magnitudes with tiny and huge ones via a random exponent.
    const double v = std::ldexp(uniform(rng), static_cast<int>(rng() % 120) - 60);
    const std::string text = FormatDouble(v);
    EXPECT_EQ(std::strtod(text.c_str(), nullptr), v) << text;
  }
}

TEST(FormatDoubleTest, AlwaysLooksLikeAReal) {
  EXPECT_EQ(FormatDouble(128.0), "128.0");
  EXPECT_EQ(FormatDouble(0.0), "0.0");
  EXPECT_EQ(FormatDouble(-3.0), "-3.0");
  EXPECT_EQ(FormatDouble(0.1), "0.1");
  EXPECT_EQ(FormatDouble(4.8), "4.8");
  EXPECT_EQ(FormatDouble(1e-7), "1e-07");
}

TEST(WriteFileAtomicTest, ReplacesContentsAndLeavesNoTemporaries) {
  const fs::path dir =
      fs::path(::testing::TempDir()) / ("vb_atomic_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  WriteFileAtomic(path, "first version, longer\n");
  WriteFileAtomic(path, "second\n");
  std::stringstream read;
  read << std::ifstream(path).rdbuf();
  EXPECT_EQ(read.str(), "second\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 1);

  // A directory that does not exist: an IoError (the system's failure, not bad input; DEF-2)
  // naming the target path.
  const std::string bad = (dir / "missing" / "out.txt").string();
  try {
    WriteFileAtomic(bad, "x");
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(e.path(), bad);
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vb::io
