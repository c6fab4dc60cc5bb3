// TaskSpec: one environment of the benchmark (world + 10 start/goal pairs), as loaded from a task
// file (docs/task_format.md). Plain data: no I/O here; tools/io/task_io.h reads and writes it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/surface_class.h"

namespace vb::terrain {

// Regular grid of terrain heights. Vertex (row r, col c) is at
//   x = -size_x/2 + c * spacing_x,  y = +size_y/2 - r * spacing_y
// i.e. row 0 is the north (+y) edge and column 0 the west (-x) edge, as image pixels.
struct HeightGrid {
  int rows = 0;
  int cols = 0;
  std::vector<double> heights_m;  // row-major, rows*cols
  double At(int r, int c) const { return heights_m[static_cast<size_t>(r) * cols + c]; }
};

// Semantics: rows x cols patches covering the world; patch (0,0) is the north-west corner.
struct PatchGrid {
  int rows = 0;
  int cols = 0;
  std::vector<SurfaceClass> classes;  // row-major
  std::vector<double> friction;       // row-major; rigid: Coulomb mu; deformable: 0 (unused)
  SurfaceClass ClassAt(int r, int c) const { return classes[static_cast<size_t>(r) * cols + c]; }
  double FrictionAt(int r, int c) const { return friction[static_cast<size_t>(r) * cols + c]; }
};

// A rock: a shape of the task's rock kind (obstacle_shape.h) with the bounding box of the
// original's collision box (4.4, 4.4, 3.8) m * scale * task.scale, resting on the terrain.
constexpr double kRockSideAtScale1_m = 4.4;   // the rock box's side at both scales 1
struct RockSpec {
  double x_m = 0.0;
  double y_m = 0.0;
  double scale = 1.0;
  // Seed of this rock's boulder shape: derived, not stored in the file (AssignShapeSeeds in
  // obstacle_shape.h: from the task's generator seed and the rock's index), kept by copies
  // (scaled tasks, perceived subsets).
  uint64_t shape_seed = 0;
};
// A tree: a shape of the task's tree kind with the bounding box (1, 1, 5) m * task.scale,
// standing on the terrain at (x, y).
struct TreeSpec {
  double x_m = 0.0;
  double y_m = 0.0;
};

// The shape of one obstacle kind (task format v2 `obstacles.shapes`, docs/task_format.md).
//   kBox:     the original's axis-aligned collision box (format v1 means this for both kinds)
//   kBoulder: a seeded lumpy dome, convex, stretched to the rock's box (rocks only)
//   kTrunk:   a 12-sided prism of the tree box's width and height (trees only)
//   kMesh:    the convex hull of a mesh's vertices (metres at scale 1, loaded by tools/io)
enum class ObstacleShapeKind { kBox, kBoulder, kTrunk, kMesh };
struct ObstacleShapeSpec {
  ObstacleShapeKind kind = ObstacleShapeKind::kBox;
  std::string mesh_file;              // kMesh: the path as written in the task file
  std::vector<Vec3> mesh_vertices_m;  // kMesh: the mesh's vertices, filled by the loader
};

struct StartGoalPair {
  Vec2 start_m = Vec2::Zero();
  Vec2 goal_m = Vec2::Zero();
  std::vector<Vec2> path_m;  // precomputed global path, start to goal (world x, y)
};

enum class ElevationLevel { kLow, kMid, kHigh };
enum class TerrainType { kRigid, kDeformable, kMixed };
enum class ObstacleDensity { kSparse, kMedium, kDense };

struct TaskLabels {
  ElevationLevel elevation = ElevationLevel::kLow;
  TerrainType terrain = TerrainType::kRigid;
  ObstacleDensity density = ObstacleDensity::kSparse;
  // Classes present in the patch grid, ascending by id (see ClassesPresent).
  std::vector<SurfaceClass> classes;
};

// The distinct classes of a patch grid, ascending by id (the label stored in task files).
std::vector<SurfaceClass> ClassesPresent(const PatchGrid& patches);

// Limits of a loadable task (tools/io/task_io.cc checks them; vb_gen and vb_import keep their
// outputs inside them). Far beyond any benchmark world (128 m, scale 1, 1/6 or 1/10, rock scales
// 0.7 to 1.2, at most ~40 obstacles): they exist so that absurd but finite values fail as bad
// input instead of overflowing a derived length or cell count, or running for hours.
struct TaskLimits {
  static constexpr double kMinWorldScale = 1e-3;
  static constexpr double kMaxWorldScale = 1e3;
  static constexpr double kMaxRockScale = 100.0;   // a rock's box must also fit in the world
  static constexpr double kMaxWorldSize_m = 1e5;   // per side
  // Heights (both ends of height_range_m) within +-1e9 m: one ulp of a coordinate there is
  // 1.2e-7 m, still far below the contact and soil geometry (millimetres). Beyond it the
  // positions of a vehicle or a rock lose the digits the simulation needs (NEW-14 of the probe at
  // 8ff4def: at 1e12 .. 1e308 a boulder's hull came out flat or inside out).
  static constexpr double kMaxAbsHeight_m = 1e9;
  static constexpr size_t kMaxObstacles = 10000;   // rocks + trees
  static constexpr int kMaxImageSide = 8192;       // height image pixels per side
  static constexpr size_t kMaxNameLength = 128;
};

// Why `name` cannot be a task name, or "" if it can. A task name is a file-name component of
// every output (<name>_p<K>_...json): 1 to 128 characters of [A-Za-z0-9_.-], not starting with
// '.' or '-', so it can neither leave the output directory nor hide a file, and it is ASCII.
std::string TaskNameProblem(const std::string& name);

struct TaskSpec {
  static constexpr int kFormatVersion = 2;   // written; versions 1 and 2 are read

  std::string name;          // e.g. "env042"
  std::string source_file;   // task file path as given (for messages and provenance)
  uint64_t generator_seed = 0;  // seed the environment was generated from (provenance)

  // World geometry: a size_x_m x size_y_m rectangle centred at the origin.
  double size_x_m = 128.0;
  double size_y_m = 128.0;
  double scale = 1.0;          // 1, 1/6, 1/10: scale variant (all lengths already scaled)
  std::string height_image;    // path of the height image, relative to the task file
  double min_height_m = 0.0;   // height of pixel value 0
  double max_height_m = 0.0;   // height of the largest pixel value (255 or 65535)
  HeightGrid heights;          // decoded from height_image by the loader

  PatchGrid patches;
  std::vector<RockSpec> rocks;
  std::vector<TreeSpec> trees;
  // Shapes per kind. A TaskSpec made in code has boxes (format v1's meaning); the generator and
  // a v2 file without `shapes` have the benchmark's family, boulders and trunks.
  ObstacleShapeSpec rock_shape;
  ObstacleShapeSpec tree_shape;
  std::vector<StartGoalPair> pairs;
  TaskLabels labels;
};

std::string_view ElevationLevelName(ElevationLevel v);
std::string_view TerrainTypeName(TerrainType v);
std::string_view ObstacleDensityName(ObstacleDensity v);

}  // namespace vb::terrain
