// WriteWorldPicture (tools/io/world_picture.h): a PNG of the expected size, written atomically.
#include "io/world_picture.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "support/worlds.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

uint32_t BigEndian32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(s[at + i]);
  return v;
}

TEST(WorldPictureTest, WritesTwoPanelPngOfTheGridSize) {
  terrain::TaskSpec task = test::PlaneTask(64.0, 0.1, 0.0);
  task.rocks.push_back({5.0, 5.0, 1.0});
  const fs::path dir = fs::path(::testing::TempDir()) / ("vb_picture_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string path = (dir / "w.png").string();
  WriteWorldPicture(task, path);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  const std::string png = ss.str();
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  // IHDR: width = 2 panels of 65 cells x 3 px + 8 px gap, height = 65 x 3 + 40 px legend
  EXPECT_EQ(BigEndian32(png, 16), 2u * 65 * 3 + 8);
  EXPECT_EQ(BigEndian32(png, 20), 65u * 3 + 40);
  for (const auto& e : fs::directory_iterator(dir)) {
    EXPECT_EQ(e.path().filename(), "w.png");  // no temporary left behind
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace vb::io
