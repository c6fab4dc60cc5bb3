// Tests for the importer's reading side (tools/io/original_io.h) and the original's derived grids
// (src/terrain/original_world.cc) on the five original Verti-Bench sample worlds in
// $VB_SHARED_DIR/verti_bench_samples: the obstacle map equals obs*.bmp and the label grid equals
// labels*.npy exactly; the imported task reproduces the geometry; bad inputs are clear errors.
#include "io/original_io.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_error.h"
#include "vb/terrain/grid_planner.h"
#include "vb/terrain/original_world.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;

const std::string kSamples = VB_SHARED_DIR "/verti_bench_samples";

struct Sample {
  int world;
  const char* level;
  std::string File(const std::string& stem, const std::string& ext, bool with_level) const {
    const std::string suffix = with_level ? "_" + std::string(level) : "";
    return kSamples + "/" + stem + std::to_string(world) + suffix + ext;
  }
  std::string Config() const { return File("config", ".yaml", true); }
  std::string World() const { return File("world", ".bmp", false); }
  std::string Labels() const { return File("labels", ".npy", true); }
  std::string Obs() const { return File("obs", ".bmp", true); }
};
const Sample kAll[] = {{1, "high"}, {42, "low"}, {62, "mid"}, {66, "mid"}, {94, "low"}};

#define SKIP_WITHOUT_SAMPLES()                                                              \
  if (!fs::exists(kSamples + "/config42_low.yaml")) {                                      \
    GTEST_SKIP() << "original Verti-Bench samples not found in " << kSamples                \
                 << " (VB_SHARED_DIR at build time); importer checks against them skipped"; \
  }

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

TEST(OriginalWorldTest, ObstacleMapAndLabelGridEqualTheShippedOnes) {
  SKIP_WITHOUT_SAMPLES();
  for (const Sample& s : kAll) {
    SCOPED_TRACE(s.Config());
    const OriginalWorldFiles files = LoadOriginalWorld(s.Config(), s.World(), s.Labels());
    const terrain::GrayImage obs = ReadGrayImage(s.Obs());
    const terrain::GrayImage derived = terrain::OriginalObstacleMap(files.config, files.world);
    ASSERT_EQ(derived.rows, obs.rows);
    ASSERT_EQ(derived.cols, obs.cols);
    int differing = 0, obstacle_pixels = 0;
    for (size_t i = 0; i < obs.pixels.size(); ++i) {
      differing += derived.pixels[i] != obs.pixels[i];
      obstacle_pixels += obs.pixels[i] == 255;
    }
    EXPECT_EQ(differing, 0);
    EXPECT_GT(obstacle_pixels, 100);  // 20-40 rocks of 9-25 pixels each
    const std::vector<int32_t> labels = terrain::OriginalLabelGrid(files.config.patches, 129, 129);
    if (files.config.terrain_type != terrain::TerrainType::kMixed) {
      EXPECT_EQ(labels, files.labels);  // the whole 129 x 129 grid, not only patch corners
      continue;
    }
    // Mixed worlds: the original converted leftover soil patches to clay by rewriting their
    // 8 x 8 blocks only (§4.3), so on the image's last row/column such a patch keeps its former
    // soil label, which the config no longer records. Everything else matches exactly.
    int remnants = 0;
    for (int r = 0; r < 129; ++r) {
      for (int c = 0; c < 129; ++c) {
        const size_t i = static_cast<size_t>(r) * 129 + c;
        if (labels[i] == files.labels[i]) continue;
        const bool edge = r == 128 || c == 128;
        EXPECT_TRUE(edge && labels[i] == 0 && files.labels[i] >= 7)
            << "pixel (" << r << ", " << c << "): derived " << labels[i] << ", shipped "
            << files.labels[i];
        ++remnants;
      }
    }
    EXPECT_LE(remnants, 2 * 129);
  }
}

TEST(OriginalWorldTest, ImportedTaskReproducesTheGeometry) {
  SKIP_WITHOUT_SAMPLES();
  for (const Sample& s : kAll) {
    SCOPED_TRACE(s.Config());
    const OriginalWorldFiles files = LoadOriginalWorld(s.Config(), s.World(), "");
    EXPECT_TRUE(files.labels.empty());
    const terrain::TaskSpec task =
        terrain::TaskFromOriginal(files.config, files.world, "orig", s.Config());
    EXPECT_EQ(task.size_x_m, 128.0);
    EXPECT_EQ(task.size_y_m, 128.0);
    ASSERT_EQ(task.heights.rows, 129);
    const double max_h = files.config.max_height_m;
    EXPECT_EQ(max_h, 16.0 * (s.level[0] == 'l' ? 0.3 : s.level[0] == 'm' ? 0.6 : 1.0));
    for (int r = 0; r < 129; r += 16) {
      for (int c = 0; c < 129; c += 16) {
        EXPECT_DOUBLE_EQ(task.heights.At(r, c), files.world.At(r, c) / 255.0 * max_h);
      }
    }
    ASSERT_EQ(task.rocks.size(), files.config.rocks.size());
    for (size_t i = 0; i < task.rocks.size(); ++i) {
      EXPECT_EQ(task.rocks[i].x_m, files.config.rocks[i].x_m);
      EXPECT_EQ(task.rocks[i].scale, files.config.rocks[i].scale);
    }
    EXPECT_EQ(task.trees.size(), files.config.trees.size());
    ASSERT_EQ(task.pairs.size(), 10u);
    EXPECT_NEAR(task.pairs[0].start_m.x(), 60.0, 1e-9);
    EXPECT_NEAR(task.pairs[0].goal_m.x(), -60.0, 1e-9);
    EXPECT_NEAR(task.pairs[1].start_m.y(), 35.2671, 1e-4);
    const terrain::OccupancyGrid inflated =
        terrain::Inflate(terrain::RasterizeObstacles(task), terrain::PlannerInflationCells(task));
    for (const terrain::StartGoalPair& pair : task.pairs) {
      ASSERT_GE(pair.path_m.size(), 2u);
      for (size_t i = 1; i < pair.path_m.size(); ++i) {
        const terrain::Cell c = inflated.CellOf(pair.path_m[i]);
        EXPECT_FALSE(inflated.Occupied(c.row, c.col));
      }
    }
    EXPECT_EQ(task.patches.classes, files.config.patches.classes);
    EXPECT_EQ(task.patches.friction, files.config.patches.friction);
  }
}

class OriginalIoErrorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = (fs::path(::testing::TempDir()) /
            ("vb_original_io_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(getpid())))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string Path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  // config42_low.yaml with the first occurrence of `find` replaced; *line receives its line.
  std::string EditedConfig(const std::string& find, const std::string& replace, int* line) {
    std::string text = ReadAll(kAll[1].Config());
    const size_t pos = text.find(find);
    EXPECT_NE(pos, std::string::npos) << find;
    *line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
    text.replace(pos, find.size(), replace);
    std::ofstream(Path("config.yaml"), std::ios::binary) << text;
    return Path("config.yaml");
  }

  // An error with no line (file-level): message starts with the path and contains `what`.
  template <typename Load>
  void ExpectFileError(Load load, const std::string& file, const std::string& what) {
    try {
      load();
      ADD_FAILURE() << "no error; expected one about " << file;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_EQ(std::string(e.what()).rfind(file + ": ", 0), 0u) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  }
  std::string dir_;
};

TEST_F(OriginalIoErrorTest, WrongImageSize) {
  SKIP_WITHOUT_SAMPLES();
  terrain::GrayImage small;
  small.rows = small.cols = 128;
  small.pixels.assign(128 * 128, 50);
  WriteGrayImage(small, Path("small.png"));
  ExpectFileError([&] { LoadOriginalWorld(kAll[1].Config(), Path("small.png"), ""); },
                  Path("small.png"), "wrong image size 128 x 128 (original worlds are 129 x 129");
}

TEST_F(OriginalIoErrorTest, ConfigNotMatchingItsImage) {
  SKIP_WITHOUT_SAMPLES();
  int line = 0;
  const std::string cfg = EditedConfig("length: 64.5", "length: 64.0", &line);
  test::ExpectInputError([&] { LoadOriginalWorld(cfg, kAll[1].World(), ""); }, cfg, line,
                         "terrain.length", "implies 128.0 pixels, but the world image");
  const std::string cfg2 = EditedConfig("max_height: 4.8", "max_height: 9.6", &line);
  test::ExpectInputError([&] { LoadOriginalWorld(cfg2, kAll[1].World(), ""); }, cfg2, line,
                         "terrain.max_height", "does not match difficulty 'low'");
  // an obstacle map given as the world image
  ExpectFileError([&] { LoadOriginalWorld(kAll[1].Config(), kAll[1].Obs(), ""); }, kAll[1].Obs(),
                  "contains pixel value 255");
  // labels of another world
  ExpectFileError([&] { LoadOriginalWorld(kAll[1].Config(), kAll[1].World(), kAll[0].Labels()); },
                  kAll[0].Labels(), "does not match patch");
}

TEST_F(OriginalIoErrorTest, UnknownClassAndKeys) {
  SKIP_WITHOUT_SAMPLES();
  int line = 0;
  const std::string cfg = EditedConfig("terrain_type: concrete", "terrain_type: lava", &line);
  try {
    LoadOriginalWorld(cfg, kAll[1].World(), "");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), line);
    EXPECT_NE(e.key().find("textures["), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("unknown terrain class 'lava'"), std::string::npos);
  }
  const std::string cfg2 = EditedConfig("obstacles_flag: true", "obstacles_flagg: true", &line);
  test::ExpectInputError([&] { LoadOriginalWorld(cfg2, kAll[1].World(), ""); }, cfg2, line,
                         "obstacles_flagg", "unknown key");
  const std::string cfg3 = EditedConfig("terrain_type: rigid", "terrain_type: muddy", &line);
  test::ExpectInputError([&] { LoadOriginalWorld(cfg3, kAll[1].World(), ""); }, cfg3, line,
                         "terrain_type", "unknown terrain_type 'muddy'");
}

TEST_F(OriginalIoErrorTest, NpyErrors) {
  std::ofstream(Path("bad.npy"), std::ios::binary) << "not numpy";
  int rows = 0, cols = 0;
  ExpectFileError([&] { ReadNpyInt32(Path("bad.npy"), &rows, &cols); }, Path("bad.npy"),
                  "not a .npy file");
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (2, 2), }";
  header.resize(118, ' ');
  header += '\n';
  std::string bytes = std::string("\x93NUMPY\x01\x00", 8);
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>(header.size() >> 8);
  bytes += header + std::string(32, '\0');
  std::ofstream(Path("f8.npy"), std::ios::binary) << bytes;
  ExpectFileError([&] { ReadNpyInt32(Path("f8.npy"), &rows, &cols); }, Path("f8.npy"),
                  "expected little-endian int32");
}

}  // namespace
}  // namespace vb::io
