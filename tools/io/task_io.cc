#include "io/task_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "io/image_file.h"
#include "io/mesh_loader.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"
#include "vb/terrain/obstacle_shape.h"

namespace vb::io {
namespace {

using terrain::ElevationLevel;
using terrain::HeightGrid;
using terrain::ObstacleDensity;
using terrain::SurfaceClass;
using terrain::TaskSpec;
using terrain::TerrainType;
using Limits = terrain::TaskLimits;

constexpr char kFormatName[] = "vb-task";
// Friction above 2 is not a plausible Coulomb coefficient for any ground: a typo, not data.
constexpr double kMaxFriction = 2.0;

// String -> enum for the three label kinds, driven by the Name functions of task.h so the file
// spelling has one definition.
template <typename E, size_t N>
E ParseLabel(const StrictNode& node, const std::array<E, N>& values,
             std::string_view (*name_of)(E)) {
  const std::string text = node.AsString();
  std::string valid;
  for (E v : values) {
    if (name_of(v) == text) return v;
    valid += (valid.empty() ? "" : ", ") + std::string(name_of(v));
  }
  node.Fail("unknown value '" + text + "' (valid: " + valid + ")");
}

constexpr std::array<ElevationLevel, 3> kElevations = {
    ElevationLevel::kLow, ElevationLevel::kMid, ElevationLevel::kHigh};
constexpr std::array<TerrainType, 3> kTerrainTypes = {
    TerrainType::kRigid, TerrainType::kDeformable, TerrainType::kMixed};
constexpr std::array<ObstacleDensity, 3> kDensities = {
    ObstacleDensity::kSparse, ObstacleDensity::kMedium, ObstacleDensity::kDense};

// Fails unless (x, y) lies in the world rectangle (edges included).
void CheckInWorld(const StrictNode& node, const TaskSpec& task, double x, double y) {
  const double hx = 0.5 * task.size_x_m;
  const double hy = 0.5 * task.size_y_m;
  if (std::abs(x) > hx || std::abs(y) > hy) {
    node.Fail("point (" + FormatDouble(x) + ", " + FormatDouble(y) + ") is outside the world [" +
              FormatDouble(-hx) + ", " + FormatDouble(hx) + "] x [" + FormatDouble(-hy) + ", " +
              FormatDouble(hy) + "]");
  }
}

Vec2 ReadPointInWorld(const StrictNode& node, const TaskSpec& task) {
  const Vec2 p = node.AsVec2();
  CheckInWorld(node, task, p.x(), p.y());
  return p;
}

// Returns the height_image node, for messages about the image decoded later.
StrictNode ReadWorld(const StrictNode& node, TaskSpec& task) {
  const StrictMap world = node.AsMap({"size_m", "scale", "height_image", "height_range_m"});
  const std::vector<StrictNode> size = world.Required("size_m").AsList(2, 2);
  task.size_x_m = size[0].AsPositive();
  task.size_y_m = size[1].AsPositive();
  for (const StrictNode& side : size) {
    if (side.AsDouble() > Limits::kMaxWorldSize_m) {
      side.Fail("must be at most " + FormatDouble(Limits::kMaxWorldSize_m) + " m, got " +
                FormatDouble(side.AsDouble()));
    }
  }
  // Bounded, not just > 0: every length of the world (obstacle boxes, planner inflation, goal
  // radius) is a multiple of it, and a huge factor overflows them (DEF-1 of the probe).
  const StrictNode scale = world.Required("scale");
  task.scale = scale.AsPositive();
  if (task.scale < Limits::kMinWorldScale || task.scale > Limits::kMaxWorldScale) {
    scale.Fail("must be in [" + FormatDouble(Limits::kMinWorldScale) + ", " +
               FormatDouble(Limits::kMaxWorldScale) + "], got " + FormatDouble(task.scale));
  }
  const StrictNode range_node = world.Required("height_range_m");
  const Vec2 range = range_node.AsVec2();
  if (range[1] < range[0]) {
    range_node.Fail("max height " + FormatDouble(range[1]) + " is below min height " +
                    FormatDouble(range[0]));
  }
  if (!std::isfinite(range[1] - range[0])) {
    range_node.Fail("the height span " + FormatDouble(range[0]) + " .. " +
                    FormatDouble(range[1]) + " is not a finite number");
  }
  if (std::abs(range[0]) > Limits::kMaxAbsHeight_m || std::abs(range[1]) > Limits::kMaxAbsHeight_m) {
    range_node.Fail("heights must lie within +-" + FormatDouble(Limits::kMaxAbsHeight_m) +
                    " m (beyond, coordinates lose the precision contacts need), got " +
                    FormatDouble(range[0]) + " .. " + FormatDouble(range[1]));
  }
  task.min_height_m = range[0];
  task.max_height_m = range[1];
  const StrictNode image = world.Required("height_image");
  task.height_image = image.AsString();
  if (task.height_image.empty()) image.Fail("height image path is empty");
  return image;
}

// A height image file's largest size: an 8192 x 8192 16-bit image stored raw, plus headers.
constexpr uint64_t kMaxImageFileBytes = 160ull << 20;

// Width and height from a PNG's IHDR chunk; false if the file is not a PNG (or is too short).
bool PngHeaderSize(const std::string& path, int* cols, int* rows) {
  std::ifstream in(path, std::ios::binary);
  unsigned char b[24] = {};
  if (!in.read(reinterpret_cast<char*>(b), sizeof(b))) return false;
  static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (!std::equal(kSignature, kSignature + 8, b) || std::string(b + 12, b + 16) != "IHDR") {
    return false;
  }
  auto be32 = [&](int at) {
    return (uint32_t{b[at]} << 24) | (uint32_t{b[at + 1]} << 16) | (uint32_t{b[at + 2]} << 8) |
           uint32_t{b[at + 3]};
  };
  // Clamped to int: PNG allows up to 2^31 - 1, anything above the limit is refused anyway.
  *cols = static_cast<int>(std::min<uint32_t>(be32(16), 0x7fffffff));
  *rows = static_cast<int>(std::min<uint32_t>(be32(20), 0x7fffffff));
  return true;
}

// Decodes the height image: pixel (r, c) is vertex (r, c), h = min + p / pmax * (max - min).
HeightGrid ReadHeights(const StrictNode& image_node, const TaskSpec& task) {
  namespace fs = std::filesystem;
  const fs::path task_dir = fs::path(task.source_file).parent_path();
  const std::string image_path = (task_dir / task.height_image).string();
  // A directory, FIFO or /dev/zero would be "does not exist", block, or never end.
  const std::string problem = InputFileProblem(image_path, kMaxImageFileBytes);
  if (!problem.empty()) image_node.Fail("height image '" + image_path + "' " + problem);
  // A PNG header can claim any size; check it before the decoder allocates for it.
  int header_cols = 0, header_rows = 0;
  if (PngHeaderSize(image_path, &header_cols, &header_rows) &&
      (header_cols > Limits::kMaxImageSide || header_rows > Limits::kMaxImageSide)) {
    image_node.Fail("height image '" + image_path + "' is " + std::to_string(header_cols) + "x" +
                    std::to_string(header_rows) + " pixels; at most " +
                    std::to_string(Limits::kMaxImageSide) + " per side are supported");
  }
  RasterImage image;
  try {
    image = ReadRasterImage(image_path);
  } catch (const ImageDecodeError& e) {
    image_node.Fail("height image '" + image_path + "' cannot be read as an image: " + e.what());
  }
  if (image.rows > Limits::kMaxImageSide || image.cols > Limits::kMaxImageSide) {
    image_node.Fail("height image '" + image_path + "' is " + std::to_string(image.cols) + "x" +
                    std::to_string(image.rows) + " pixels; at most " +
                    std::to_string(Limits::kMaxImageSide) + " per side are supported");
  }
  if (image.channels != 1) {
    image_node.Fail("height image '" + image_path +
                    "' must be 8- or 16-bit single-channel grayscale; it has " +
                    std::to_string(image.channels) + " channel(s) of " +
                    std::to_string(image.bit_depth) + "-bit values");
  }
  if (image.rows < 2 || image.cols < 2) {
    image_node.Fail("height image '" + image_path + "' must be at least 2x2 pixels; it is " +
                    std::to_string(image.cols) + "x" + std::to_string(image.rows));
  }
  HeightGrid grid;
  grid.rows = image.rows;
  grid.cols = image.cols;
  grid.heights_m.resize(static_cast<size_t>(grid.rows) * grid.cols);
  const double pmax = image.bit_depth == 16 ? 65535.0 : 255.0;
  const double span = task.max_height_m - task.min_height_m;
  for (int r = 0; r < grid.rows; ++r) {
    for (int c = 0; c < grid.cols; ++c) {
      const double p = image.At(r, c);
      grid.heights_m[static_cast<size_t>(r) * grid.cols + c] = task.min_height_m + p / pmax * span;
    }
  }
  return grid;
}

// Returns the labels.classes node (absent: a null node), checked after the semantics are read.
std::optional<StrictNode> ReadLabels(const StrictNode& node, TaskSpec& task) {
  const StrictMap labels = node.AsMap({"elevation", "terrain", "density", "classes"});
  task.labels.elevation =
      ParseLabel(labels.Required("elevation"), kElevations, &terrain::ElevationLevelName);
  task.labels.terrain =
      ParseLabel(labels.Required("terrain"), kTerrainTypes, &terrain::TerrainTypeName);
  task.labels.density =
      ParseLabel(labels.Required("density"), kDensities, &terrain::ObstacleDensityName);
  if (!labels.Has("classes")) return std::nullopt;
  return labels.Required("classes");
}

// labels.classes is derived data: when present it must name exactly the classes of the patch
// grid, ascending by id (a mismatch means the file was edited inconsistently).
void CheckClassesLabel(const std::optional<StrictNode>& node, TaskSpec& task) {
  task.labels.classes = terrain::ClassesPresent(task.patches);
  if (!node) return;
  std::vector<SurfaceClass> listed;
  for (const StrictNode& item : node->AsList(1)) {
    const std::string name = item.AsString();
    const std::optional<SurfaceClass> c = terrain::SurfaceClassFromName(name);
    if (!c) {
      item.Fail("unknown terrain class '" + name + "' (valid: " + terrain::SurfaceClassNames() +
                ")");
    }
    listed.push_back(*c);
  }
  if (listed != task.labels.classes) {
    std::string want;
    for (SurfaceClass c : task.labels.classes) {
      want += (want.empty() ? "" : ", ") + std::string(terrain::SurfaceClassName(c));
    }
    node->Fail("must list the classes present in semantics.classes, ascending by id: [" + want +
               "]");
  }
}

void ReadSemantics(const StrictNode& node, TaskSpec& task) {
  const StrictMap semantics = node.AsMap({"grid", "classes", "friction"});
  const std::vector<StrictNode> grid = semantics.Required("grid").AsList(2, 2);
  const int64_t rows = grid[0].AsInt();
  const int64_t cols = grid[1].AsInt();
  // 4096 patches per side is far beyond any world (the original has 16): a bound on allocation.
  if (rows < 1 || rows > 4096) {
    grid[0].Fail("rows must be in [1, 4096], got " + std::to_string(rows));
  }
  if (cols < 1 || cols > 4096) {
    grid[1].Fail("cols must be in [1, 4096], got " + std::to_string(cols));
  }
  terrain::PatchGrid& patches = task.patches;
  patches.rows = static_cast<int>(rows);
  patches.cols = static_cast<int>(cols);

  for (const StrictNode& row : semantics.Required("classes").AsList(rows, rows)) {
    for (const StrictNode& cell : row.AsList(cols, cols)) {
      const std::string name = cell.AsString();
      const std::optional<SurfaceClass> c = terrain::SurfaceClassFromName(name);
      if (!c) {
        cell.Fail("unknown terrain class '" + name + "' (valid: " + terrain::SurfaceClassNames() +
                  ")");
      }
      patches.classes.push_back(*c);
    }
  }
  size_t index = 0;
  for (const StrictNode& row : semantics.Required("friction").AsList(rows, rows)) {
    for (const StrictNode& cell : row.AsList(cols, cols)) {
      const double mu = cell.AsDouble();
      const SurfaceClass c = patches.classes[index++];
      if (terrain::IsDeformable(c) && mu != 0.0) {
        cell.Fail("friction of a deformable patch (" + std::string(terrain::SurfaceClassName(c)) +
                  ") must be 0 (soil parameters come from the class), got " + FormatDouble(mu));
      }
      if (!terrain::IsDeformable(c) && !(mu > 0.0 && mu <= kMaxFriction)) {
        cell.Fail("friction of a rigid patch (" + std::string(terrain::SurfaceClassName(c)) +
                  ") must be in (0, 2], got " + FormatDouble(mu));
      }
      patches.friction.push_back(mu);
    }
  }
}

// One entry of obstacles.shapes: a kind name, or {mesh: path} (relative to the task file).
terrain::ObstacleShapeSpec ReadShape(const StrictNode& node, const TaskSpec& task, bool rock) {
  terrain::ObstacleShapeSpec shape;
  if (node.IsMap()) {
    const StrictMap map = node.AsMap({"mesh"});
    const StrictNode file = map.Required("mesh");
    shape.kind = terrain::ObstacleShapeKind::kMesh;
    shape.mesh_file = file.AsString();
    if (shape.mesh_file.empty()) file.Fail("empty mesh path");
    if (shape.mesh_file.find('\0') != std::string::npos) file.Fail("mesh path contains NUL");
    namespace fs = std::filesystem;
    const std::string resolved =
        (fs::path(task.source_file).parent_path() / shape.mesh_file).string();
    shape.mesh_vertices_m = LoadMeshVertices(resolved, file.file(), file.line(), file.key());
    return shape;
  }
  const std::string name = node.AsString();
  const char* valid = rock ? "box, boulder or {mesh: FILE}" : "box, trunk or {mesh: FILE}";
  if (!terrain::ParseObstacleShapeKind(name, &shape.kind) ||
      shape.kind == terrain::ObstacleShapeKind::kMesh ||
      shape.kind == (rock ? terrain::ObstacleShapeKind::kTrunk
                          : terrain::ObstacleShapeKind::kBoulder)) {
    node.Fail("unknown shape '" + name + "'; valid: " + valid);
  }
  return shape;
}

void ReadObstacles(const StrictNode& node, TaskSpec& task, int version) {
  // Version 1 has no shapes and means the original's boxes; version 2 defaults to the
  // benchmark's family (boulders and trunks).
  const StrictMap obstacles = version == 1 ? node.AsMap({"rocks", "trees"})
                                           : node.AsMap({"shapes", "rocks", "trees"});
  if (version == 1) {
    task.rock_shape.kind = terrain::ObstacleShapeKind::kBox;
    task.tree_shape.kind = terrain::ObstacleShapeKind::kBox;
  } else {
    task.rock_shape.kind = terrain::ObstacleShapeKind::kBoulder;
    task.tree_shape.kind = terrain::ObstacleShapeKind::kTrunk;
    if (obstacles.Has("shapes")) {
      const StrictMap shapes = obstacles.Required("shapes").AsMap({"rock", "tree"});
      if (shapes.Has("rock")) task.rock_shape = ReadShape(shapes.Required("rock"), task, true);
      if (shapes.Has("tree")) task.tree_shape = ReadShape(shapes.Required("tree"), task, false);
    }
  }
  // Each obstacle becomes a convex body with its own broadphase entry: a million trees is not a
  // world but a setup that runs for hours.
  const std::vector<StrictNode> rocks = obstacles.Required("rocks").AsList();
  const std::vector<StrictNode> trees = obstacles.Required("trees").AsList();
  if (rocks.size() + trees.size() > Limits::kMaxObstacles) {
    node.Fail(std::to_string(rocks.size()) + " rocks and " + std::to_string(trees.size()) +
              " trees; at most " + std::to_string(Limits::kMaxObstacles) +
              " obstacles are supported");
  }
  const double smaller_side_m = std::min(task.size_x_m, task.size_y_m);
  for (const StrictNode& item : rocks) {
    const StrictMap rock = item.AsMap({"x", "y", "scale"});
    terrain::RockSpec spec;
    spec.x_m = rock.Required("x").AsDouble();
    spec.y_m = rock.Required("y").AsDouble();
    const StrictNode scale = rock.Required("scale");
    spec.scale = scale.AsPositive();
    // The box side is 4.4 m x scale x world scale: a rock wider than the world is a typo, and
    // its footprint walk and cell counts would overflow (DEF-1).
    const double side_m = terrain::kRockSideAtScale1_m * spec.scale * task.scale;
    if (spec.scale > Limits::kMaxRockScale || side_m > smaller_side_m) {
      scale.Fail("must be at most " + FormatDouble(Limits::kMaxRockScale) +
                 " and the rock's box (" + FormatDouble(terrain::kRockSideAtScale1_m) +
                 " m x scale x world scale = " + FormatDouble(side_m) +
                 " m) must fit in the world (" + FormatDouble(smaller_side_m) + " m); got " +
                 FormatDouble(spec.scale));
    }
    CheckInWorld(item, task, spec.x_m, spec.y_m);
    task.rocks.push_back(spec);
  }
  for (const StrictNode& item : trees) {
    const StrictMap tree = item.AsMap({"x", "y"});
    terrain::TreeSpec spec;
    spec.x_m = tree.Required("x").AsDouble();
    spec.y_m = tree.Required("y").AsDouble();
    CheckInWorld(item, task, spec.x_m, spec.y_m);
    task.trees.push_back(spec);
  }
}

void ReadPairs(const StrictNode& node, TaskSpec& task) {
  for (const StrictNode& item : node.AsList(1)) {
    const StrictMap pair = item.AsMap({"start", "goal", "path"});
    terrain::StartGoalPair spec;
    spec.start_m = ReadPointInWorld(pair.Required("start"), task);
    spec.goal_m = ReadPointInWorld(pair.Required("goal"), task);
    for (const StrictNode& point : pair.Required("path").AsList(2)) {
      spec.path_m.push_back(ReadPointInWorld(point, task));
    }
    task.pairs.push_back(std::move(spec));
  }
}

// --- writing ---

// A string as a YAML scalar: plain when it is a simple name or path that YAML would not read as
// anything else, double-quoted otherwise.
std::string YamlString(const std::string& s) {
  // Plain scalars may start with a letter, '_', '/', "./" or "../"; a digit or '-' could read
  // as a number and most other leading characters are YAML indicators.
  const bool good_start =
      !s.empty() && (std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_' ||
                     s[0] == '/' || s.rfind("./", 0) == 0 || s.rfind("../", 0) == 0);
  const bool simple = good_start && s.find_first_not_of("abcdefghijklmnopqrstuvwxyz"
                                                        "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                        "0123456789_-./") == std::string::npos;
  static const std::array<const char*, 11> kReserved = {
      "true", "false", "null", "yes", "no", "on", "off", "y", "n", "True", "False"};
  bool reserved = false;
  for (const char* word : kReserved) reserved = reserved || s == word;
  if (simple && !reserved) return s;
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    out += ch;
  }
  return out + "\"";
}

std::string Pair(double a, double b) {
  return "[" + FormatDouble(a) + ", " + FormatDouble(b) + "]";
}

terrain::TaskSpec LoadTaskFromRoot(const StrictNode& root, const std::string& path) {
  const StrictMap top = root.AsMap({"format", "version", "name", "generator_seed", "world",
                                    "labels", "semantics", "obstacles", "pairs"});
  // Format and version first: a file of another kind or version gets that message, not a
  // confusing complaint about some key further down.
  const StrictNode format = top.Required("format");
  if (format.AsString() != kFormatName) {
    format.Fail("expected format '" + std::string(kFormatName) + "', got '" + format.AsString() +
                "'");
  }
  const StrictNode version = top.Required("version");
  if (version.AsInt() != 1 && version.AsInt() != TaskSpec::kFormatVersion) {
    version.Fail("unsupported task format version " + std::to_string(version.AsInt()) +
                 " (this build reads versions 1 and " +
                 std::to_string(TaskSpec::kFormatVersion) + ")");
  }

  TaskSpec task;
  task.source_file = path;
  const StrictNode name = top.Required("name");
  task.name = name.AsString();
  // The name becomes part of every output file name: checked here, where it enters.
  const std::string name_problem = terrain::TaskNameProblem(task.name);
  if (!name_problem.empty()) name.Fail(name_problem);
  task.generator_seed = top.Required("generator_seed").AsUint64();
  const StrictNode image = ReadWorld(top.Required("world"), task);
  const std::optional<StrictNode> classes_label = ReadLabels(top.Required("labels"), task);
  ReadSemantics(top.Required("semantics"), task);
  CheckClassesLabel(classes_label, task);
  ReadObstacles(top.Required("obstacles"), task, static_cast<int>(version.AsInt()));
  terrain::AssignShapeSeeds(&task);
  ReadPairs(top.Required("pairs"), task);
  // The image last: a task with a bad key fails fast without decoding a large image.
  task.heights = ReadHeights(image, task);
  return task;
}

}  // namespace

terrain::TaskSpec LoadTask(const std::string& path) {
  return LoadTaskFromRoot(LoadYamlFile(path), path);
}

terrain::TaskSpec LoadTaskText(const std::string& text, const std::string& path) {
  return LoadTaskFromRoot(LoadYamlText(text, path), path);
}

void SaveTask(const terrain::TaskSpec& task, const std::string& path) {
  const terrain::PatchGrid& patches = task.patches;
  VB_DEMAND(patches.classes.size() == static_cast<size_t>(patches.rows) * patches.cols);
  VB_DEMAND(patches.friction.size() == patches.classes.size());

  std::string out;
  out += "# vb task file (docs/task_format.md)\n";
  out += "format: " + std::string(kFormatName) + "\n";
  out += "version: " + std::to_string(TaskSpec::kFormatVersion) + "\n";
  out += "name: " + YamlString(task.name) + "\n";
  out += "generator_seed: " + std::to_string(task.generator_seed) + "\n";
  out += "world:\n";
  out += "  size_m: " + Pair(task.size_x_m, task.size_y_m) + "\n";
  out += "  scale: " + FormatDouble(task.scale) + "\n";
  out += "  height_image: " + YamlString(task.height_image) + "\n";
  out += "  height_range_m: " + Pair(task.min_height_m, task.max_height_m) + "\n";
  out += "labels: {elevation: " + std::string(terrain::ElevationLevelName(task.labels.elevation)) +
         ", terrain: " + std::string(terrain::TerrainTypeName(task.labels.terrain)) +
         ", density: " + std::string(terrain::ObstacleDensityName(task.labels.density)) +
         ", classes: [";
  {
    // always derived from the patches, so a saved file is consistent by construction
    std::string names;
    for (SurfaceClass c : terrain::ClassesPresent(patches)) {
      names += (names.empty() ? "" : ", ") + std::string(terrain::SurfaceClassName(c));
    }
    out += names + "]}\n";
  }

  out += "semantics:\n";
  out += "  grid: [" + std::to_string(patches.rows) + ", " + std::to_string(patches.cols) + "]\n";
  out += "  classes:\n";
  for (int r = 0; r < patches.rows; ++r) {
    out += "    - [";
    for (int c = 0; c < patches.cols; ++c) {
      out += (c ? ", " : "") + std::string(terrain::SurfaceClassName(patches.ClassAt(r, c)));
    }
    out += "]\n";
  }
  out += "  friction:\n";
  for (int r = 0; r < patches.rows; ++r) {
    out += "    - [";
    for (int c = 0; c < patches.cols; ++c) {
      out += (c ? ", " : "") + FormatDouble(patches.FrictionAt(r, c));
    }
    out += "]\n";
  }

  out += "obstacles:\n";
  {
    auto shape_text = [](const terrain::ObstacleShapeSpec& shape) {
      if (shape.kind == terrain::ObstacleShapeKind::kMesh) {
        return "{mesh: " + YamlString(shape.mesh_file) + "}";
      }
      return std::string(terrain::ObstacleShapeKindName(shape.kind));
    };
    out += "  shapes: {rock: " + shape_text(task.rock_shape) +
           ", tree: " + shape_text(task.tree_shape) + "}\n";
  }
  out += task.rocks.empty() ? "  rocks: []\n" : "  rocks:\n";
  for (const terrain::RockSpec& rock : task.rocks) {
    out += "    - {x: " + FormatDouble(rock.x_m) + ", y: " + FormatDouble(rock.y_m) +
           ", scale: " + FormatDouble(rock.scale) + "}\n";
  }
  out += task.trees.empty() ? "  trees: []\n" : "  trees:\n";
  for (const terrain::TreeSpec& tree : task.trees) {
    out += "    - {x: " + FormatDouble(tree.x_m) + ", y: " + FormatDouble(tree.y_m) + "}\n";
  }

  // One path point per line: paths are long, and this keeps diffs between versions readable.
  out += task.pairs.empty() ? "pairs: []\n" : "pairs:\n";
  for (const terrain::StartGoalPair& pair : task.pairs) {
    out += "  - start: " + Pair(pair.start_m.x(), pair.start_m.y()) + "\n";
    out += "    goal: " + Pair(pair.goal_m.x(), pair.goal_m.y()) + "\n";
    out += pair.path_m.empty() ? "    path: []\n" : "    path:\n";
    for (const Vec2& p : pair.path_m) out += "      - " + Pair(p.x(), p.y()) + "\n";
  }
  // The round trip Save -> Load is a promise: check it before writing (DEF-11 of the probe).
  LoadTaskText(out, path);
  WriteFileAtomic(path, out);
}

void WriteHeightImage(const terrain::HeightGrid& heights, double min_height_m, double max_height_m,
                      const std::string& path) {
  VB_DEMAND(heights.rows > 0 && heights.cols > 0);
  VB_DEMAND(heights.heights_m.size() == static_cast<size_t>(heights.rows) * heights.cols);
  VB_DEMAND(max_height_m >= min_height_m);
  const double span = max_height_m - min_height_m;
  std::vector<uint16_t> image(static_cast<size_t>(heights.rows) * heights.cols);
  for (int r = 0; r < heights.rows; ++r) {
    for (int c = 0; c < heights.cols; ++c) {
      // A flat range maps everything to 0; heights outside the range clamp to its ends.
      const double t = span > 0.0 ? (heights.At(r, c) - min_height_m) / span : 0.0;
      const double p = std::round(std::min(1.0, std::max(0.0, t)) * 65535.0);
      image[static_cast<size_t>(r) * heights.cols + c] = static_cast<uint16_t>(p);
    }
  }
  const std::string png = EncodePng16Gray(image.data(), heights.rows, heights.cols);
  WriteFileAtomic(path, png);
}

}  // namespace vb::io
