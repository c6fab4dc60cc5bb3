#include "io/original_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "io/image_file.h"
#include "io/yaml_strict.h"
#include "vb/engine/error.h"

namespace vb::io {
namespace {

using terrain::ElevationLevel;
using terrain::ObstacleDensity;
using terrain::OriginalConfig;
using terrain::SurfaceClass;
using terrain::TerrainType;

constexpr int kPatches = 16;
constexpr double kFullHeightM = 16.0;  // max_height = 16 * {0.3, 0.6, 1.0} (§1, GeometryDiff)

std::string Fmt(double v) { return FormatDouble(v); }

ElevationLevel ReadDifficulty(const StrictNode& node) {
  const std::string s = node.AsString();
  if (s == "low") return ElevationLevel::kLow;
  if (s == "mid") return ElevationLevel::kMid;
  if (s == "high") return ElevationLevel::kHigh;
  node.Fail("unknown difficulty '" + s + "' (valid: low, mid, high)");
}

double LevelFactor(ElevationLevel level) {
  switch (level) {
    case ElevationLevel::kLow: return 0.3;
    case ElevationLevel::kMid: return 0.6;
    case ElevationLevel::kHigh: return 1.0;
  }
  return 1.0;
}

TerrainType ReadTerrainType(const StrictNode& node) {
  const std::string s = node.AsString();
  if (s == "rigid") return TerrainType::kRigid;
  if (s == "deformable") return TerrainType::kDeformable;
  if (s == "mixed") return TerrainType::kMixed;
  node.Fail("unknown terrain_type '" + s + "' (valid: rigid, deformable, mixed)");
}

ObstacleDensity ReadDensity(const StrictNode& node) {
  const std::string s = node.AsString();
  if (s == "sparse") return ObstacleDensity::kSparse;
  if (s == "medium") return ObstacleDensity::kMedium;
  if (s == "dense") return ObstacleDensity::kDense;
  node.Fail("unknown obstacle_density '" + s + "' (valid: sparse, medium, dense)");
}

// Fails unless (x, y) lies in the task's world of half sizes (hx, hy): the task written would
// refuse it.
void CheckInWorld(const StrictNode& node, double x, double y, double hx, double hy) {
  if (std::abs(x) > hx || std::abs(y) > hy) {
    node.Fail("point (" + Fmt(x) + ", " + Fmt(y) + ") is outside the world [" + Fmt(-hx) + ", " +
              Fmt(hx) + "] x [" + Fmt(-hy) + ", " + Fmt(hy) + "]");
  }
}

terrain::OriginalObstacle ReadObstacle(const StrictNode& item, bool rock, double hx, double hy) {
  const StrictMap m = rock ? item.AsMap({"position", "scale"}) : item.AsMap({"position"});
  const StrictNode position = m.Required("position");
  const StrictMap p = position.AsMap({"x", "y", "z"});
  terrain::OriginalObstacle o;
  o.x_m = p.Required("x").AsDouble();
  o.y_m = p.Required("y").AsDouble();
  o.z_m = p.Required("z").AsDouble();
  CheckInWorld(position, o.x_m, o.y_m, hx, hy);
  if (rock) {
    // The task format's bound (task.h TaskLimits): refused here, at the config's line.
    const StrictNode scale = m.Required("scale");
    o.scale = scale.AsPositive();
    const double side_m = terrain::kRockSideAtScale1_m * o.scale;
    if (o.scale > terrain::TaskLimits::kMaxRockScale || side_m > 2.0 * std::min(hx, hy)) {
      scale.Fail("rock scale " + Fmt(o.scale) + " out of range: at most " +
                 Fmt(terrain::TaskLimits::kMaxRockScale) + ", and the rock's " + Fmt(side_m) +
                 " m box must fit in the world");
    }
  }
  return o;
}

void ReadTextures(const StrictNode& node, OriginalConfig* config) {
  terrain::PatchGrid& patches = config->patches;
  patches.rows = kPatches;
  patches.cols = kPatches;
  patches.classes.assign(kPatches * kPatches, SurfaceClass::kClay);
  patches.friction.assign(kPatches * kPatches, 0.0);
  std::vector<bool> seen(kPatches * kPatches, false);
  for (const StrictNode& item : node.AsList(kPatches * kPatches, kPatches * kPatches)) {
    const StrictMap t = item.AsMap({"index", "center_position", "terrain_type", "is_deformable",
                                    "texture_file", "friction", "restitution"});
    const StrictNode index_node = t.Required("index");
    const std::vector<StrictNode> index = index_node.AsList(2, 2);
    const int64_t i = index[0].AsInt();
    const int64_t j = index[1].AsInt();
    if (i < 0 || i >= kPatches || j < 0 || j >= kPatches) {
      index_node.Fail("patch index [" + std::to_string(i) + ", " + std::to_string(j) +
                      "] outside the 16 x 16 grid");
    }
    const size_t k = static_cast<size_t>(i * kPatches + j);
    if (seen[k]) {
      index_node.Fail("patch [" + std::to_string(i) + ", " + std::to_string(j) +
                      "] listed twice");
    }
    seen[k] = true;
    const StrictNode centre_node = t.Required("center_position");
    const StrictMap centre = centre_node.AsMap({"x", "y", "z"});
    const double cx = centre.Required("x").AsDouble();
    const double cy = centre.Required("y").AsDouble();
    centre.Required("z").AsDouble();
    // patch centre: x = -60 + 8 j, y = 60 - 8 i (§1, true for all 25,600 shipped entries)
    if (cx != -60.0 + 8.0 * j || cy != 60.0 - 8.0 * i) {
      centre_node.Fail("centre (" + Fmt(cx) + ", " + Fmt(cy) + ") does not match patch index [" +
                       std::to_string(i) + ", " + std::to_string(j) + "] (expected (" +
                       Fmt(-60.0 + 8.0 * j) + ", " + Fmt(60.0 - 8.0 * i) + "))");
    }
    const StrictNode type_node = t.Required("terrain_type");
    const std::string type = type_node.AsString();
    const std::optional<SurfaceClass> cls = terrain::SurfaceClassFromName(type);
    if (!cls) {
      type_node.Fail("unknown terrain class '" + type + "' (valid: " +
                     terrain::SurfaceClassNames() + ")");
    }
    const StrictNode def_node = t.Required("is_deformable");
    if (def_node.AsBool() != terrain::IsDeformable(*cls)) {
      def_node.Fail(std::string("is_deformable ") + (def_node.AsBool() ? "true" : "false") +
                    " contradicts class '" + type + "'");
    }
    t.Required("texture_file").AsString();
    patches.classes[k] = *cls;
    if (terrain::IsDeformable(*cls)) {
      if (t.Has("friction")) t.Required("friction").Fail("deformable patch with a friction");
    } else {
      const StrictNode mu_node = t.Required("friction");
      const double mu = mu_node.AsDouble();
      if (!(mu >= 0.1 && mu <= 1.0)) {
        mu_node.Fail("friction " + Fmt(mu) + " outside the original's [0.1, 1]");
      }
      patches.friction[k] = mu;
      t.Required("restitution").AsNonNegative();
    }
  }
}

// length_node / width_node receive the config's half-size nodes, for messages about a config
// that does not match its image.
OriginalConfig ReadConfig(const std::string& path, std::optional<StrictNode>* length_node,
                          std::optional<StrictNode>* width_node) {
  const StrictNode root = LoadYamlFile(path);
  const StrictMap top = root.AsMap({"terrain", "terrain_type", "obstacles_flag",
                                    "obstacle_density", "obstacles", "positions", "textures"});
  OriginalConfig c;
  const StrictMap terrain_map = top.Required("terrain").AsMap(
      {"difficulty", "is_flat", "length", "width", "min_height", "max_height"});
  c.difficulty = ReadDifficulty(terrain_map.Required("difficulty"));
  c.is_flat = terrain_map.Required("is_flat").AsBool();
  length_node->emplace(terrain_map.Required("length"));
  width_node->emplace(terrain_map.Required("width"));
  c.half_length_m = (*length_node)->AsPositive();
  c.half_width_m = (*width_node)->AsPositive();
  c.min_height_m = terrain_map.Required("min_height").AsDouble();
  const StrictNode max_node = terrain_map.Required("max_height");
  c.max_height_m = max_node.AsDouble();
  const double expected_max = c.min_height_m + kFullHeightM * LevelFactor(c.difficulty);
  if (std::abs(c.max_height_m - expected_max) > 1e-9) {
    max_node.Fail("max_height " + Fmt(c.max_height_m) + " does not match difficulty '" +
                  std::string(terrain::ElevationLevelName(c.difficulty)) + "' (expected " +
                  Fmt(expected_max) + " = 16 m x " + Fmt(LevelFactor(c.difficulty)) + ")");
  }
  c.terrain_type = ReadTerrainType(top.Required("terrain_type"));
  c.obstacles_flag = top.Required("obstacles_flag").AsBool();
  c.density = ReadDensity(top.Required("obstacle_density"));
  const StrictMap obstacles = top.Required("obstacles").AsMap({"rocks", "trees"});
  const std::vector<StrictNode> rocks = obstacles.Required("rocks").AsList();
  const std::vector<StrictNode> trees = obstacles.Required("trees").AsList();
  if (rocks.size() + trees.size() > terrain::TaskLimits::kMaxObstacles) {
    top.Required("obstacles").Fail("more than " +
                                   std::to_string(terrain::TaskLimits::kMaxObstacles) +
                                   " obstacles");
  }
  // The task's world spans the image's vertices: (2 * half size - 1) m, i.e. |x| <= 64 m.
  const double hx = c.half_length_m - 0.5;
  const double hy = c.half_width_m - 0.5;
  for (const StrictNode& item : rocks) c.rocks.push_back(ReadObstacle(item, true, hx, hy));
  for (const StrictNode& item : trees) c.trees.push_back(ReadObstacle(item, false, hx, hy));
  for (const StrictNode& item : top.Required("positions").AsList(1)) {
    const StrictMap pair = item.AsMap({"start", "goal"});
    terrain::StartGoalPair p;
    const StrictNode start_node = pair.Required("start");
    const StrictNode goal_node = pair.Required("goal");
    const Vec3 start = start_node.AsVec3();
    const Vec3 goal = goal_node.AsVec3();
    CheckInWorld(start_node, start.x(), start.y(), hx, hy);
    CheckInWorld(goal_node, goal.x(), goal.y(), hx, hy);
    p.start_m = start.head<2>();
    p.goal_m = goal.head<2>();
    c.pairs.push_back(p);
  }
  ReadTextures(top.Required("textures"), &c);
  // rigid worlds have no soil and deformable worlds no rigid patch (§4.3)
  const StrictNode type_node = top.Required("terrain_type");
  for (SurfaceClass cls : c.patches.classes) {
    if (c.terrain_type == TerrainType::kRigid && terrain::IsDeformable(cls)) {
      type_node.Fail("rigid world with a deformable patch (" +
                     std::string(terrain::SurfaceClassName(cls)) + ")");
    }
    if (c.terrain_type == TerrainType::kDeformable && !terrain::IsDeformable(cls)) {
      type_node.Fail("deformable world with a rigid patch (" +
                     std::string(terrain::SurfaceClassName(cls)) + ")");
    }
  }
  return c;
}

uint32_t ReadLe(const std::string& bytes, size_t offset, int n) {
  uint32_t v = 0;
  for (int i = n - 1; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(bytes[offset + i]);
  return v;
}

}  // namespace

terrain::GrayImage ReadGrayImage(const std::string& path) {
  // Original worlds are 129 x 129 bytes: 64 MiB is far above any real one, and a directory,
  // FIFO or /dev/zero is refused before OpenCV blocks on it or reads it forever.
  const std::string problem = InputFileProblem(path, kMaxYamlFileBytes);
  if (!problem.empty()) throw InputError(path, 0, "", problem);
  RasterImage image;
  try {
    image = ReadRasterImage(path);
  } catch (const ImageDecodeError& e) {
    throw InputError(path, 0, "", std::string("cannot be read as an image: ") + e.what());
  }
  if (image.channels != 1 || image.bit_depth != 8) {
    throw InputError(path, 0, "",
                     "must be an 8-bit single-channel grayscale image; it has " +
                         std::to_string(image.channels) + " channel(s) of " +
                         std::to_string(image.bit_depth) + "-bit values");
  }
  terrain::GrayImage out;
  out.rows = image.rows;
  out.cols = image.cols;
  out.pixels.resize(static_cast<size_t>(out.rows) * out.cols);
  for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = static_cast<uint8_t>(image.samples[i]);
  return out;
}

void WriteGrayImage(const terrain::GrayImage& image, const std::string& path) {
  VB_DEMAND(image.pixels.size() == static_cast<size_t>(image.rows) * image.cols);
  WriteFileAtomic(path, EncodePng8(image.pixels.data(), image.rows, image.cols, 1,
                                   static_cast<size_t>(image.cols)));
}

std::vector<int32_t> ReadNpyInt32(const std::string& path, int* rows, int* cols) {
  // A label grid is 129 x 129 int32 (66 kB); /dev/zero or /dev/urandom would be read forever.
  const std::string problem = InputFileProblem(path, kMaxYamlFileBytes);
  if (!problem.empty()) throw InputError(path, 0, "", problem);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open .npy file");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string bytes = ss.str();
  auto fail = [&](const std::string& what) -> void { throw InputError(path, 0, "", what); };
  if (bytes.size() < 10 || bytes.compare(0, 6, "\x93NUMPY") != 0) fail("not a .npy file");
  const int major = static_cast<unsigned char>(bytes[6]);
  size_t header_len = 0;
  size_t header_start = 0;
  if (major == 1) {
    header_len = ReadLe(bytes, 8, 2);
    header_start = 10;
  } else if (major == 2 || major == 3) {
    if (bytes.size() < 12) fail("truncated .npy header");
    header_len = ReadLe(bytes, 8, 4);
    header_start = 12;
  } else {
    fail("unsupported .npy version " + std::to_string(major));
  }
  if (bytes.size() < header_start + header_len) fail("truncated .npy header");
  const std::string header = bytes.substr(header_start, header_len);
  if (header.find("'descr': '<i4'") == std::string::npos) {
    fail("expected little-endian int32 data ('descr': '<i4'); header: " + header);
  }
  if (header.find("'fortran_order': False") == std::string::npos) {
    fail("expected C order ('fortran_order': False); header: " + header);
  }
  const size_t shape_pos = header.find("'shape': (");
  if (shape_pos == std::string::npos) fail("no shape in header: " + header);
  int r = 0, c = 0;
  if (std::sscanf(header.c_str() + shape_pos, "'shape': (%d, %d)", &r, &c) != 2 || r <= 0 ||
      c <= 0) {
    fail("expected a 2-D shape; header: " + header);
  }
  const size_t data_start = header_start + header_len;
  const size_t count = static_cast<size_t>(r) * c;
  // Compared by division: 4 * count can wrap for a header claiming a huge shape.
  if ((bytes.size() - data_start) % 4 != 0 || (bytes.size() - data_start) / 4 != count) {
    fail("data size " + std::to_string(bytes.size() - data_start) +
         " bytes does not match shape (" + std::to_string(r) + ", " + std::to_string(c) + ")");
  }
  std::vector<int32_t> out(count);
  for (size_t i = 0; i < count; ++i) {
    out[i] = static_cast<int32_t>(ReadLe(bytes, data_start + 4 * i, 4));
  }
  *rows = r;
  *cols = c;
  return out;
}

OriginalWorldFiles LoadOriginalWorld(const std::string& config_path, const std::string& world_path,
                                     const std::string& labels_path) {
  OriginalWorldFiles files;
  std::optional<StrictNode> length_node;
  std::optional<StrictNode> width_node;
  files.config = ReadConfig(config_path, &length_node, &width_node);
  files.world = ReadGrayImage(world_path);
  // the original requires exactly 129 x 129 (§2.1)
  if (files.world.rows != 129 || files.world.cols != 129) {
    throw InputError(world_path, 0, "",
                     "wrong image size " + std::to_string(files.world.cols) + " x " +
                         std::to_string(files.world.rows) +
                         " (original worlds are 129 x 129 pixels)");
  }
  // config and image must describe the same grid: 2 * half size = pixels (1 px per metre)
  if (2.0 * files.config.half_length_m != files.world.cols) {
    length_node->Fail("length " + Fmt(files.config.half_length_m) + " (half size) implies " +
                     Fmt(2.0 * files.config.half_length_m) + " pixels, but the world image '" +
                     world_path + "' is " + std::to_string(files.world.cols) + " wide");
  }
  if (2.0 * files.config.half_width_m != files.world.rows) {
    width_node->Fail("width " + Fmt(files.config.half_width_m) + " (half size) implies " +
                    Fmt(2.0 * files.config.half_width_m) + " pixels, but the world image '" +
                    world_path + "' is " + std::to_string(files.world.rows) + " high");
  }
  // 255 marks obstacles in the original's maps; a world image never contains it (§1.2)
  for (uint8_t p : files.world.pixels) {
    if (p == 255) {
      throw InputError(world_path, 0, "",
                       "contains pixel value 255 (an obstacle map obs*.bmp, not a world image?)");
    }
  }
  if (!labels_path.empty()) {
    int rows = 0, cols = 0;
    files.labels = ReadNpyInt32(labels_path, &rows, &cols);
    if (rows != files.world.rows || cols != files.world.cols) {
      throw InputError(labels_path, 0, "",
                       "shape (" + std::to_string(rows) + ", " + std::to_string(cols) +
                           ") does not match the world image (" +
                           std::to_string(files.world.rows) + ", " +
                           std::to_string(files.world.cols) + ")");
    }
    const terrain::PatchGrid& patches = files.config.patches;
    for (int i = 0; i < patches.rows; ++i) {
      for (int j = 0; j < patches.cols; ++j) {
        const int32_t label = files.labels[static_cast<size_t>(8 * i) * cols + 8 * j];
        const int32_t expected = static_cast<int32_t>(patches.ClassAt(i, j));
        if (label != expected) {
          throw InputError(labels_path, 0, "",
                           "label " + std::to_string(label) + " at pixel (" +
                               std::to_string(8 * i) + ", " + std::to_string(8 * j) +
                               ") does not match patch [" + std::to_string(i) + ", " +
                               std::to_string(j) + "] of " + config_path + " (" +
                               std::string(terrain::SurfaceClassName(patches.ClassAt(i, j))) +
                               " = " + std::to_string(expected) + ")");
        }
      }
    }
  }
  return files;
}

}  // namespace vb::io
