// Tests for tools/io/task_io.cc: a valid load, the Save/Load round trip, and every class of
// input error with its file, line and key.
#include "io/task_io.h"

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/bmp.h"
#include "support/input_error.h"

#include "vb/engine/error.h"

namespace vb::io {
namespace {

namespace fs = std::filesystem;
using terrain::SurfaceClass;
using terrain::TaskSpec;

// A 4 m x 6 m world, 2 x 3 patches, 3 x 4 pixel height image. Line numbers matter: the error
// tests below edit single lines and expect them in the messages.
constexpr char kTinyTask[] = R"(format: vb-task
version: 1
name: tiny
generator_seed: 7
world:
  size_m: [4.0, 6.0]
  scale: 1.0
  height_image: tiny.png
  height_range_m: [0.5, 2.5]
labels: {elevation: mid, terrain: mixed, density: sparse}
semantics:
  grid: [2, 3]
  classes:
    - [dirt, mud, rock]
    - [sand, grass, clay]
  friction:
    - [0.6, 0.0, 0.9]
    - [0.0, 0.45, 0.7]
obstacles:
  rocks:
    - {x: 1.0, y: -1.5, scale: 0.5}
  trees:
    - {x: -1.0, y: 2.0}
pairs:
  - start: [1.5, 0.0]
    goal: [-1.5, 0.0]
    path: [[1.5, 0.0], [0.0, 0.5], [-1.5, 0.0]]
  - start: [0.0, 2.5]
    goal: [0.0, -2.5]
    path:
      - [0.0, 2.5]
      - [0.0, -2.5]
)";

std::string ReadAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

terrain::HeightGrid MakeGrid(int rows, int cols, double min_h, double max_h) {
  terrain::HeightGrid grid;
  grid.rows = rows;
  grid.cols = cols;
  for (int i = 0; i < rows * cols; ++i) {
    grid.heights_m.push_back(min_h + (max_h - min_h) * (i % 7) / 6.0);
  }
  return grid;
}

class TaskIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = (fs::path(::testing::TempDir()) /
            ("vb_task_io_" + std::string(info->name()) + "_" + std::to_string(getpid())))
               .string();
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    WriteHeightImage(MakeGrid(4, 3, 0.5, 2.5), 0.5, 2.5, Path("tiny.png"));
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Path(const std::string& name) const { return (fs::path(dir_) / name).string(); }

  std::string WriteText(const std::string& name, const std::string& text) const {
    std::ofstream(Path(name), std::ios::binary) << text;
    return Path(name);
  }

  // kTinyTask with the first line containing `find` replaced by `replace` ("" deletes it).
  static std::string Edit(const std::string& find, const std::string& replace) {
    std::istringstream in(kTinyTask);
    std::string out, line;
    bool done = false;
    while (std::getline(in, line)) {
      if (!done && line.find(find) != std::string::npos) {
        done = true;
        if (replace.empty()) continue;
        line = replace;
      }
      out += line + "\n";
    }
    EXPECT_TRUE(done) << "no line contains " << find;
    return out;
  }

  // Loads `text` and expects an InputError at `line` with `key` whose message contains `what`.
  void ExpectError(const std::string& text, int line, const std::string& key,
                   const std::string& what) {
    const std::string file = WriteText("task.yaml", text);
    test::ExpectInputError([&] { LoadTask(file); }, file, line, key, what);
  }

  std::string dir_;
};

TEST_F(TaskIoTest, LoadsValidTask) {
  const std::string file = WriteText("task.yaml", kTinyTask);
  const TaskSpec task = LoadTask(file);
  EXPECT_EQ(task.name, "tiny");
  EXPECT_EQ(task.source_file, file);
  EXPECT_EQ(task.generator_seed, 7u);
  EXPECT_EQ(task.size_x_m, 4.0);
  EXPECT_EQ(task.size_y_m, 6.0);
  EXPECT_EQ(task.scale, 1.0);
  EXPECT_EQ(task.height_image, "tiny.png");
  EXPECT_EQ(task.min_height_m, 0.5);
  EXPECT_EQ(task.max_height_m, 2.5);
  EXPECT_EQ(task.labels.elevation, terrain::ElevationLevel::kMid);
  EXPECT_EQ(task.labels.terrain, terrain::TerrainType::kMixed);
  EXPECT_EQ(task.labels.density, terrain::ObstacleDensity::kSparse);

  ASSERT_EQ(task.patches.rows, 2);
  ASSERT_EQ(task.patches.cols, 3);
  EXPECT_EQ(task.patches.ClassAt(0, 1), SurfaceClass::kMud);
  EXPECT_EQ(task.patches.ClassAt(1, 2), SurfaceClass::kClay);
  EXPECT_EQ(task.patches.FrictionAt(1, 1), 0.45);
  EXPECT_EQ(task.patches.FrictionAt(0, 1), 0.0);

  ASSERT_EQ(task.rocks.size(), 1u);
  EXPECT_EQ(task.rocks[0].y_m, -1.5);
  EXPECT_EQ(task.rocks[0].scale, 0.5);
  ASSERT_EQ(task.trees.size(), 1u);
  EXPECT_EQ(task.trees[0].x_m, -1.0);
  ASSERT_EQ(task.pairs.size(), 2u);
  EXPECT_EQ(task.pairs[0].goal_m, Vec2(-1.5, 0.0));
  ASSERT_EQ(task.pairs[0].path_m.size(), 3u);
  EXPECT_EQ(task.pairs[0].path_m[1], Vec2(0.0, 0.5));
  ASSERT_EQ(task.pairs[1].path_m.size(), 2u);

  // Image rows x cols = vertex rows x cols; the pixel pattern of MakeGrid comes back.
  const terrain::HeightGrid expected = MakeGrid(4, 3, 0.5, 2.5);
  ASSERT_EQ(task.heights.rows, 4);
  ASSERT_EQ(task.heights.cols, 3);
  for (size_t i = 0; i < expected.heights_m.size(); ++i) {
    EXPECT_NEAR(task.heights.heights_m[i], expected.heights_m[i], 2.0 / 65535);
  }
}

TEST_F(TaskIoTest, Decodes8BitBmp) {
  // 8-bit: h = min + p / 255 * (max - min), pixel (r, c) = vertex (r, c), row 0 north.
  std::ofstream(Path("gray.bmp"), std::ios::binary)
      << test::MakeBmp(3, 2, {0, 51, 255, 102, 0, 17});
  const TaskSpec task = LoadTask(WriteText("task.yaml", Edit("height_image:",
                                                             "  height_image: gray.bmp")));
  ASSERT_EQ(task.heights.rows, 2);
  ASSERT_EQ(task.heights.cols, 3);
  EXPECT_DOUBLE_EQ(task.heights.At(0, 0), 0.5);
  EXPECT_DOUBLE_EQ(task.heights.At(0, 1), 0.5 + 51.0 / 255 * 2.0);
  EXPECT_DOUBLE_EQ(task.heights.At(0, 2), 2.5);
  EXPECT_DOUBLE_EQ(task.heights.At(1, 0), 0.5 + 102.0 / 255 * 2.0);
  EXPECT_DOUBLE_EQ(task.heights.At(1, 2), 0.5 + 17.0 / 255 * 2.0);
}

TEST_F(TaskIoTest, ImagePathIsRelativeToTaskFile) {
  fs::create_directories(Path("tasks"));
  fs::create_directories(Path("worlds"));
  WriteHeightImage(MakeGrid(2, 2, 0.5, 2.5), 0.5, 2.5, Path("worlds/w.png"));
  const std::string text = Edit("height_image:", "  height_image: ../worlds/w.png");
  const TaskSpec task = LoadTask(WriteText("tasks/t.yaml", text));
  EXPECT_EQ(task.height_image, "../worlds/w.png");
  EXPECT_EQ(task.heights.rows, 2);
}

TEST_F(TaskIoTest, RoundTrip) {
  TaskSpec task;
  task.name = "env042";
  task.generator_seed = 18446744073709551615u;  // the full uint64 range survives
  task.size_x_m = 128.0;
  task.size_y_m = 96.5;
  task.scale = 1.0 / 6.0;
  task.height_image = "env042.png";
  task.min_height_m = -0.1;
  task.max_height_m = 4.8;
  task.heights = MakeGrid(5, 7, -0.1, 4.8);
  task.heights.heights_m[3] = 1.2345678901234;
  task.patches.rows = 2;
  task.patches.cols = 2;
  task.patches.classes = {SurfaceClass::kConcrete, SurfaceClass::kSnow, SurfaceClass::kWood,
                          SurfaceClass::kGravel};
  task.patches.friction = {0.5409885399236531, 0.0, 0.1 + 0.2, 1e-7};
  task.rocks = {{26.1, -16.7, 0.95}, {-64.0, 48.25, 1.0 / 3.0}};
  task.trees = {{4.6, -5.7}};
  task.pairs.resize(2);
  task.pairs[0].start_m = Vec2(60.0, 0.0);
  task.pairs[0].goal_m = Vec2(-60.0, 0.0);
  task.pairs[0].path_m = {Vec2(60.0, 0.0), Vec2(59.0, 0.1 / 3.0), Vec2(-60.0, 0.0)};
  task.pairs[1].start_m = Vec2(0.0, 48.25);
  task.pairs[1].goal_m = Vec2(0.0, -48.25);
  task.pairs[1].path_m = {task.pairs[1].start_m, task.pairs[1].goal_m};
  task.labels = {terrain::ElevationLevel::kHigh, terrain::TerrainType::kDeformable,
                 terrain::ObstacleDensity::kMedium, terrain::ClassesPresent(task.patches)};

  WriteHeightImage(task.heights, task.min_height_m, task.max_height_m, Path("env042.png"));
  SaveTask(task, Path("env042.yaml"));
  const TaskSpec back = LoadTask(Path("env042.yaml"));

  EXPECT_EQ(back.name, task.name);
  EXPECT_EQ(back.source_file, Path("env042.yaml"));
  EXPECT_EQ(back.generator_seed, task.generator_seed);
  EXPECT_EQ(back.size_x_m, task.size_x_m);
  EXPECT_EQ(back.size_y_m, task.size_y_m);
  EXPECT_EQ(back.scale, task.scale);
  EXPECT_EQ(back.height_image, task.height_image);
  EXPECT_EQ(back.min_height_m, task.min_height_m);
  EXPECT_EQ(back.max_height_m, task.max_height_m);
  ASSERT_EQ(back.heights.rows, task.heights.rows);
  ASSERT_EQ(back.heights.cols, task.heights.cols);
  const double quantum = (task.max_height_m - task.min_height_m) / 65535;
  for (size_t i = 0; i < task.heights.heights_m.size(); ++i) {
    EXPECT_NEAR(back.heights.heights_m[i], task.heights.heights_m[i], 0.5 * quantum + 1e-12);
  }
  EXPECT_EQ(back.patches.rows, task.patches.rows);
  EXPECT_EQ(back.patches.cols, task.patches.cols);
  EXPECT_EQ(back.patches.classes, task.patches.classes);
  EXPECT_EQ(back.patches.friction, task.patches.friction);  // bit-exact doubles
  ASSERT_EQ(back.rocks.size(), task.rocks.size());
  for (size_t i = 0; i < task.rocks.size(); ++i) {
    EXPECT_EQ(back.rocks[i].x_m, task.rocks[i].x_m);
    EXPECT_EQ(back.rocks[i].y_m, task.rocks[i].y_m);
    EXPECT_EQ(back.rocks[i].scale, task.rocks[i].scale);
  }
  ASSERT_EQ(back.trees.size(), 1u);
  EXPECT_EQ(back.trees[0].x_m, 4.6);
  EXPECT_EQ(back.trees[0].y_m, -5.7);
  ASSERT_EQ(back.pairs.size(), task.pairs.size());
  for (size_t i = 0; i < task.pairs.size(); ++i) {
    EXPECT_EQ(back.pairs[i].start_m, task.pairs[i].start_m);
    EXPECT_EQ(back.pairs[i].goal_m, task.pairs[i].goal_m);
    EXPECT_EQ(back.pairs[i].path_m, task.pairs[i].path_m);
  }
  EXPECT_EQ(back.labels.elevation, task.labels.elevation);
  EXPECT_EQ(back.labels.terrain, task.labels.terrain);
  EXPECT_EQ(back.labels.density, task.labels.density);
  EXPECT_EQ(back.labels.classes,
            (std::vector<SurfaceClass>{SurfaceClass::kConcrete, SurfaceClass::kGravel,
                                       SurfaceClass::kWood, SurfaceClass::kSnow}));
  // the saved file lists them, ascending by id
  EXPECT_NE(ReadAll(Path("env042.yaml")).find("classes: [concrete, gravel, wood, snow]}"),
            std::string::npos);

  // Saving the loaded task gives the same bytes (stable output), and writes leave no temp files.
  SaveTask(back, Path("again.yaml"));
  std::stringstream a, b;
  a << std::ifstream(Path("env042.yaml")).rdbuf();
  b << std::ifstream(Path("again.yaml")).rdbuf();
  EXPECT_EQ(a.str(), b.str());
  for (const fs::directory_entry& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
  }
}

// Names that YAML would read as something else (or not at all) are quoted on save.
TEST_F(TaskIoTest, SavedStringsRoundTrip) {
  TaskSpec task = LoadTask(WriteText("task.yaml", kTinyTask));
  fs::create_directories(Path("sub"));
  WriteHeightImage(MakeGrid(2, 2, 0.5, 2.5), 0.5, 2.5, Path("sub/w.png"));
  task.height_image = "./sub/w.png";
  for (const std::string name : {"yes", "1e5", "null", "007", "a.b-c_d"}) {
    task.name = name;
    SaveTask(task, Path("saved.yaml"));
    EXPECT_EQ(LoadTask(Path("saved.yaml")).name, name);
  }
  EXPECT_EQ(LoadTask(Path("saved.yaml")).height_image, "./sub/w.png");
  // A name the loader refuses (it would become a path, DEF-3) is refused on save: no file.
  for (const std::string name : {"a b: c", "-x", "../x", "quote\"back\\slash", "[x]"}) {
    task.name = name;
    EXPECT_THROW(SaveTask(task, Path("bad.yaml")), InputError) << name;
    EXPECT_FALSE(fs::exists(Path("bad.yaml"))) << name;
  }
}

// DEF-1, DEF-3, DEF-11 and DEF-14 of the probe: bounds where a task is loaded.
TEST_F(TaskIoTest, ErrorBoundsOfScalesSizesNamesAndStrings) {
  ExpectError(Edit("scale: 1.0", "  scale: 1e308"), 7, "world.scale", "must be in [0.001, 1000.0]");
  ExpectError(Edit("scale: 1.0", "  scale: 0.0009"), 7, "world.scale", "must be in [0.001");
  ExpectError(Edit("- {x: 1.0, y: -1.5", "    - {x: 1.0, y: -1.5, scale: 1e308}"), 21,
              "obstacles.rocks[0].scale", "must be at most 100.0");
  // 4.4 m x 1.0 is wider than this 4 m world.
  ExpectError(Edit("- {x: 1.0, y: -1.5", "    - {x: 1.0, y: -1.5, scale: 1.0}"), 21,
              "obstacles.rocks[0].scale", "must fit in the world (4.0 m)");
  ExpectError(Edit("size_m:", "  size_m: [4.0, 1e6]"), 6, "world.size_m[1]", "at most 1e+05 m");
  ExpectError(Edit("height_range_m", "  height_range_m: [-1e308, 1e308]"), 9,
              "world.height_range_m", "not a finite number");
  ExpectError(Edit("name: tiny", "name: ../../pwn"), 3, "name", "may contain only letters");
  ExpectError(Edit("name: tiny", "name: .hidden"), 3, "name", "must not start with '.'");
  ExpectError(Edit("height_image", "  height_image: \"tiny.png\\0junk\""), 8,
              "world.height_image", "string contains a NUL");
}

// A subnormal number is a valid double (FormatDouble writes them): read, not refused (DEF-11).
TEST_F(TaskIoTest, SubnormalNumbersLoad) {
  const TaskSpec task =
      LoadTask(WriteText("t.yaml", Edit("height_range_m", "  height_range_m: [1e-320, 2.5]")));
  EXPECT_EQ(task.min_height_m, 1e-320);
  ExpectError(Edit("height_range_m", "  height_range_m: [1e-400, 2.5]"), 9,
              "world.height_range_m[0]", "expected a number");
}

TEST_F(TaskIoTest, HeightImageQuantisation) {
  terrain::HeightGrid grid;
  grid.rows = 2;
  grid.cols = 2;
  grid.heights_m = {0.0, 10.0, 5.0, -3.0};  // -3 lies below the range and clamps to 0
  WriteHeightImage(grid, 0.0, 10.0, Path("q.png"));
  const TaskSpec task = LoadTask(WriteText("task.yaml", Edit("height_image:",
                                                             "  height_image: q.png")));
  // The task's range is [0.5, 2.5]: pixel 0, 65535 and round(0.5 * 65535) = 32768.
  EXPECT_DOUBLE_EQ(task.heights.At(0, 0), 0.5);
  EXPECT_DOUBLE_EQ(task.heights.At(0, 1), 2.5);
  EXPECT_DOUBLE_EQ(task.heights.At(1, 0), 0.5 + 32768.0 / 65535 * 2.0);
  EXPECT_DOUBLE_EQ(task.heights.At(1, 1), 0.5);
}

TEST_F(TaskIoTest, ErrorUnknownKey) {
  ExpectError(Edit("scale: 1.0", "  scale: 1.0\n  colour: red"), 8, "world.colour",
              "unknown key 'colour'");
  ExpectError(Edit("start: [0.0, 2.5]", "  - start: [0.0, 2.5]\n    speed: 3"), 29,
              "pairs[1].speed", "allowed: start, goal, path");
}

TEST_F(TaskIoTest, ErrorMissingKey) {
  ExpectError(Edit("scale: 1.0", ""), 5, "world.scale", "missing required key 'scale'");
}

TEST_F(TaskIoTest, ErrorDuplicateKey) {
  ExpectError(Edit("generator_seed", "generator_seed: 7\nname: again"), 5, "name",
              "duplicate key");
}

TEST_F(TaskIoTest, ErrorWrongType) {
  ExpectError(Edit("scale: 1.0", "  scale: big"), 7, "world.scale", "expected a number");
  ExpectError(Edit("scale: 1.0", "  scale: \"1.0\""), 7, "world.scale", "quoted string");
  ExpectError(Edit("size_m:", "  size_m: 4.0"), 6, "world.size_m", "expected a list");
  ExpectError(Edit("size_m:", "  size_m: [4.0, 6.0, 1.0]"), 6, "world.size_m",
              "exactly 2 items");
  ExpectError(Edit("generator_seed", "generator_seed: -7"), 4, "generator_seed",
              "non-negative integer");
  ExpectError(Edit("labels:", "labels: [mid, mixed, sparse]"), 10, "labels", "expected a map");
}

TEST_F(TaskIoTest, ErrorNonPositiveSizeOrScale) {
  ExpectError(Edit("size_m:", "  size_m: [4.0, 0.0]"), 6, "world.size_m[1]", "must be > 0");
  ExpectError(Edit("scale: 1.0", "  scale: -1.0"), 7, "world.scale", "must be > 0");
  ExpectError(Edit("- {x: 1.0, y: -1.5", "    - {x: 1.0, y: -1.5, scale: 0}"), 21,
              "obstacles.rocks[0].scale", "must be > 0");
}

TEST_F(TaskIoTest, ErrorFriction) {
  ExpectError(Edit("- [0.6, 0.0, 0.9]", "    - [0.6, 0.0, -0.9]"), 17,
              "semantics.friction[0][2]", "must be in (0, 2]");
  ExpectError(Edit("- [0.6, 0.0, 0.9]", "    - [0.0, 0.0, 0.9]"), 17,
              "semantics.friction[0][0]", "rigid patch (dirt)");
  ExpectError(Edit("- [0.0, 0.45, 0.7]", "    - [0.3, 0.45, 0.7]"), 18,
              "semantics.friction[1][0]", "deformable patch (sand) must be 0");
}

TEST_F(TaskIoTest, ErrorGridMismatch) {
  ExpectError(Edit("grid:", "  grid: [3, 3]"), 13, "semantics.classes", "exactly 3 items");
  ExpectError(Edit("- [0.0, 0.45, 0.7]", "    - [0.0, 0.45]"), 18, "semantics.friction[1]",
              "exactly 3 items");
  ExpectError(Edit("grid:", "  grid: [0, 3]"), 12, "semantics.grid[0]", "rows must be");
}

TEST_F(TaskIoTest, ErrorHeightRange) {
  ExpectError(Edit("height_range_m", "  height_range_m: [2.5, 0.5]"), 9, "world.height_range_m",
              "below min height");
}

TEST_F(TaskIoTest, ErrorOutsideWorld) {
  ExpectError(Edit("goal: [-1.5, 0.0]", "    goal: [-2.5, 0.0]"), 26, "pairs[0].goal",
              "outside the world");
  ExpectError(Edit("- [0.0, -2.5]", "      - [0.0, -3.5]"), 32, "pairs[1].path[1]",
              "outside the world");
  ExpectError(Edit("- {x: -1.0", "    - {x: -1.0, y: 3.01}"), 23, "obstacles.trees[0]",
              "outside the world");
}

TEST_F(TaskIoTest, ErrorUnknownClass) {
  ExpectError(Edit("- [dirt, mud, rock]", "    - [dirt, lava, rock]"), 14,
              "semantics.classes[0][1]",
              "unknown terrain class 'lava' (valid: clay, concrete, dirt, grass, gravel, rock, "
              "wood, mud, sand, snow)");
}

TEST_F(TaskIoTest, ErrorUnknownLabel) {
  ExpectError(Edit("labels:", "labels: {elevation: mid, terrain: mixed, density: packed}"), 10,
              "labels.density", "unknown value 'packed' (valid: sparse, medium, dense)");
}

TEST_F(TaskIoTest, ClassesLabelIsDerivedOrChecked) {
  // absent: derived from the patches
  const TaskSpec task = LoadTask(WriteText("task.yaml", kTinyTask));
  EXPECT_EQ(task.labels.classes,
            (std::vector<SurfaceClass>{SurfaceClass::kClay, SurfaceClass::kDirt,
                                       SurfaceClass::kGrass, SurfaceClass::kRock,
                                       SurfaceClass::kMud, SurfaceClass::kSand}));
  // present and right: accepted
  const std::string good =
      "labels: {elevation: mid, terrain: mixed, density: sparse, classes: [clay, dirt, grass, "
      "rock, mud, sand]}";
  EXPECT_EQ(LoadTask(WriteText("good.yaml", Edit("labels:", good))).labels.classes,
            task.labels.classes);
  // present and wrong (a class missing, or the wrong order): an error naming the right list
  ExpectError(Edit("labels:",
                   "labels: {elevation: mid, terrain: mixed, density: sparse, classes: [clay]}"),
              10, "labels.classes",
              "must list the classes present in semantics.classes, ascending by id: [clay, dirt, "
              "grass, rock, mud, sand]");
  ExpectError(Edit("labels:",
                   "labels: {elevation: mid, terrain: mixed, density: sparse, classes: [lava]}"),
              10, "labels.classes[0]", "unknown terrain class 'lava'");
}

TEST_F(TaskIoTest, ErrorFormatAndVersion) {
  ExpectError(Edit("version:", "version: 3"), 2, "version", "unsupported task format version 3");
  ExpectError(Edit("format:", "format: vb-tusk"), 1, "format", "expected format 'vb-task'");
  ExpectError(Edit("version:", ""), 1, "version", "missing required key");
}

TEST_F(TaskIoTest, ErrorYamlSyntax) {
  ExpectError(Edit("size_m:", "  size_m: [4.0, 6.0]]"), 6, "", "YAML syntax error");
}

TEST_F(TaskIoTest, ErrorNotAMap) {
  ExpectError("- just\n- a list\n", 1, "", "expected a map");
}

TEST_F(TaskIoTest, ErrorMissingTaskFile) {
  try {
    LoadTask(Path("absent.yaml"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), Path("absent.yaml"));
    EXPECT_NE(std::string(e.what()).find("absent.yaml: does not exist"), std::string::npos)
        << e.what();
  }
}

TEST_F(TaskIoTest, ErrorMissingImage) {
  ExpectError(Edit("height_image:", "  height_image: nothere.png"), 8, "world.height_image",
              "nothere.png' does not exist");
}

TEST_F(TaskIoTest, ErrorUnreadableImage) {
  WriteText("bad.png", "this is not a PNG file");
  ExpectError(Edit("height_image:", "  height_image: bad.png"), 8, "world.height_image",
              "bad.png' cannot be read as an image");
}

TEST_F(TaskIoTest, ErrorColourImage) {
  std::ofstream(Path("rgb.bmp"), std::ios::binary)
      << test::MakeBmp(3, 3, std::vector<uint8_t>(9, 80), {24});
  ExpectError(Edit("height_image:", "  height_image: rgb.bmp"), 8, "world.height_image",
              "rgb.bmp' must be 8- or 16-bit single-channel grayscale");
}

TEST_F(TaskIoTest, ErrorTooSmallImage) {
  WriteHeightImage(MakeGrid(1, 5, 0.0, 1.0), 0.0, 1.0, Path("line.png"));
  ExpectError(Edit("height_image:", "  height_image: line.png"), 8, "world.height_image",
              "at least 2x2 pixels; it is 5x1");
}

// The original Verti-Bench world images (129 x 129, 8-bit BMP) load as they are.
TEST_F(TaskIoTest, LoadsOriginalWorldImage) {
  const std::string world = VB_SHARED_DIR "/verti_bench_samples/world1.bmp";
  if (!fs::exists(world)) GTEST_SKIP() << world << " not present";
  std::string edited = Edit("height_range_m", "  height_range_m: [0.0, 16.0]");
  edited.replace(edited.find("height_image: tiny.png"), 22, "height_image: " + world);
  const TaskSpec task = LoadTask(WriteText("task.yaml", edited));
  EXPECT_EQ(task.heights.rows, 129);
  EXPECT_EQ(task.heights.cols, 129);
  double lo = 1e9, hi = -1e9;
  for (double h : task.heights.heights_m) lo = std::min(lo, h), hi = std::max(hi, h);
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 16.0);
  EXPECT_GT(hi, lo);
}

}  // namespace
}  // namespace vb::io

namespace vb::io {
namespace {

// Format v2: obstacles.shapes. Version 1 means the original's boxes, version 2 without shapes
// means the benchmark's family; a mesh is resolved relative to the task file.
TEST_F(TaskIoTest, ObstacleShapesByVersion) {
  EXPECT_EQ(LoadTask(WriteText("v1.yaml", kTinyTask)).rock_shape.kind,
            terrain::ObstacleShapeKind::kBox);
  EXPECT_EQ(LoadTask(WriteText("v1.yaml", kTinyTask)).tree_shape.kind,
            terrain::ObstacleShapeKind::kBox);
  const std::string v2 = Edit("version:", "version: 2");
  const TaskSpec defaults = LoadTask(WriteText("v2.yaml", v2));
  EXPECT_EQ(defaults.rock_shape.kind, terrain::ObstacleShapeKind::kBoulder);
  EXPECT_EQ(defaults.tree_shape.kind, terrain::ObstacleShapeKind::kTrunk);
  EXPECT_NE(defaults.rocks[0].shape_seed, 0u);
  // shapes: in v1 it is an unknown key
  const std::string shapes_line = "  shapes: {rock: box, tree: trunk}";
  auto with_shapes = [&](const std::string& text, const std::string& line) {
    return std::string(text).replace(text.find("obstacles:\n") + 11, 0, line + "\n");
  };
  const TaskSpec mixed = LoadTask(WriteText("mixed.yaml", with_shapes(v2, shapes_line)));
  EXPECT_EQ(mixed.rock_shape.kind, terrain::ObstacleShapeKind::kBox);
  EXPECT_EQ(mixed.tree_shape.kind, terrain::ObstacleShapeKind::kTrunk);
  ExpectError(with_shapes(kTinyTask, shapes_line), 20, "obstacles.shapes", "unknown key");
  ExpectError(with_shapes(v2, "  shapes: {rock: trunk}"), 20, "obstacles.shapes.rock",
              "unknown shape 'trunk'; valid: box, boulder or {mesh: FILE}");
  ExpectError(with_shapes(v2, "  shapes: {tree: pine}"), 20, "obstacles.shapes.tree",
              "unknown shape 'pine'");
  // a mesh, relative to the task file; saved and loaded back
  fs::copy_file(std::string(VB_SOURCE_DIR) + "/data/meshes/rock_small.obj", Path("rock.obj"));
  const TaskSpec mesh =
      LoadTask(WriteText("mesh.yaml", with_shapes(v2, "  shapes: {rock: {mesh: rock.obj}}")));
  EXPECT_EQ(mesh.rock_shape.kind, terrain::ObstacleShapeKind::kMesh);
  EXPECT_EQ(mesh.rock_shape.mesh_file, "rock.obj");
  EXPECT_EQ(mesh.rock_shape.mesh_vertices_m.size(), 12u);
  SaveTask(mesh, Path("saved.yaml"));
  const TaskSpec again = LoadTask(Path("saved.yaml"));
  EXPECT_EQ(again.rock_shape.mesh_vertices_m, mesh.rock_shape.mesh_vertices_m);
  EXPECT_NE(ReadAll(Path("saved.yaml")).find("shapes: {rock: {mesh: rock.obj}, tree: trunk}"),
            std::string::npos);
  ExpectError(with_shapes(v2, "  shapes: {rock: {mesh: nothing.obj}}"), 20,
              "obstacles.shapes.rock.mesh", "nothing.obj': does not exist");
}

}  // namespace
}  // namespace vb::io
