// vb_gen: generates one benchmark environment (task file + 16-bit height image) from a seed.
// Thin: argument parsing over GenerateTask (src/terrain/generator.cc) and tools/io.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <string_view>

#include <optional>
#include <utility>

#include "io/cli_args.h"
#include "io/task_io.h"
#include "io/world_picture.h"
#include "vb/engine/error.h"
#include "vb/terrain/task.h"
#include "vb/terrain/generator.h"
#include "vb/terrain/scale.h"

namespace {

namespace fs = std::filesystem;
using vb::terrain::ElevationLevel;
using vb::terrain::ObstacleDensity;
using vb::terrain::TerrainType;

constexpr const char* kUsage = R"(usage:
       vb_gen --env K --out TASKDIR [--image-dir IMGDIR] [--name NAME] [--scale F] [--picture FILE]
       vb_gen --seed S --name NAME --elevation LEVEL --terrain TYPE --density DENSITY
              --out TASKDIR [--image-dir IMGDIR] [--scale F] [--picture FILE]

Generates one environment (docs/generator.md): a rugged 129 x 129 height field at 1 m (128 m x
128 m world) calibrated per elevation level against the original Verti-Bench worlds, 16 x 16
semantics patches, rocks and trees placed with the original benchmark's rules, and the 10
start/goal pairs on the 60 m circle, each with a global A* path on the obstacle grid inflated by
4 m. The same arguments always produce byte-identical files.

  --env K            benchmark environment K in [0, 99]: seed K, name envKKK and the labels fixed
                     by K (docs/generator.md); tasks/envKKK.yaml is exactly this output
  --seed S           generator seed, an unsigned 64-bit integer
  --name NAME        environment name, e.g. env042; file stem of the outputs
  --elevation LEVEL  low | mid | high
  --terrain TYPE     rigid | deformable | mixed
  --density DENSITY  sparse | medium | dense: 10/20/40 rocks and 1/2/3 trees
  --scale F          scale variant for smaller vehicles: every length times F (e.g. 1/6, 1/10,
                     0.5; default 1); give a different --name or --out for the variant
  --out TASKDIR      directory of the task file TASKDIR/NAME.yaml (required; created if missing)
  --image-dir IMGDIR directory of the height image IMGDIR/NAME.png (default: TASKDIR/../data/
                     worlds); the task file refers to it by a path relative to TASKDIR
  --picture FILE     also write a PNG picture of the world (height shading, semantics,
                     obstacles, paths; docs/generator.md)
  --help             this text
  --version          the version and git commit of this build

Without --env, --seed, --name, --elevation, --terrain and --density are all required.
Prints the elevation statistics of the generated world (as reference_verti_bench.md §9).
Exit codes: 0 success, 2 bad arguments or unwritable output, 1 other errors.
)";

struct Options {
  bool help = false;
  bool version = false;
  bool have_seed = false;
  bool have_name = false;
  vb::terrain::GeneratorOptions gen;
  bool have_elevation = false, have_terrain = false, have_density = false;
  bool have_env = false;
  double scale = 1.0;
  std::string out_dir;
  std::string image_dir;
  std::string picture;
};

template <typename E, size_t N>
E ParseChoice(const std::string& flag, const std::string& text, const E (&values)[N],
              std::string_view (*name)(E)) {
  std::string valid;
  for (E v : values) {
    if (name(v) == text) return v;
    valid += (valid.empty() ? "" : " | ") + std::string(name(v));
  }
  throw vb::InputError("", 0, flag, "'" + text + "' is not one of " + valid);
}

Options ParseArgs(int argc, char** argv) {
  Options o;
  vb::io::ArgReader args(argc, argv);
  while (args.Next()) {
    const std::string& a = args.arg();
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "--seed") {
      o.gen.seed = args.U64Value();
      o.have_seed = true;
    } else if (a == "--name") {
      o.gen.name = args.Value();
      const std::string problem = vb::terrain::TaskNameProblem(o.gen.name);
      if (!problem.empty()) throw vb::InputError("", 0, a, problem);
      o.have_name = true;
    } else if (a == "--elevation") {
      static constexpr ElevationLevel kAll[] = {ElevationLevel::kLow, ElevationLevel::kMid,
                                                ElevationLevel::kHigh};
      o.gen.elevation = ParseChoice(a, args.Value(), kAll, vb::terrain::ElevationLevelName);
      o.have_elevation = true;
    } else if (a == "--terrain") {
      static constexpr TerrainType kAll[] = {TerrainType::kRigid, TerrainType::kDeformable,
                                             TerrainType::kMixed};
      o.gen.terrain = ParseChoice(a, args.Value(), kAll, vb::terrain::TerrainTypeName);
      o.have_terrain = true;
    } else if (a == "--density") {
      static constexpr ObstacleDensity kAll[] = {ObstacleDensity::kSparse, ObstacleDensity::kMedium,
                                                 ObstacleDensity::kDense};
      o.gen.density = ParseChoice(a, args.Value(), kAll, vb::terrain::ObstacleDensityName);
      o.have_density = true;
    } else if (a == "--env") {
      const uint64_t k = args.U64Value(0, vb::terrain::kBenchmarkEnvironments - 1);
      const std::string name = o.gen.name;
      o.gen = vb::terrain::BenchmarkEnvironment(static_cast<int>(k));
      if (o.have_name) o.gen.name = name;
      o.have_env = true;
    } else if (a == "--scale") {
      o.scale = args.ScaleValue();
    } else if (a == "--picture") {
      o.picture = args.Value();
    } else if (a == "--out") {
      o.out_dir = args.Value();
    } else if (a == "--image-dir") {
      o.image_dir = args.Value();
    } else {
      args.Unknown();
    }
  }
  if (o.help || o.version) return o;
  if (o.have_env) {
    for (const auto& [given, flag] : {std::pair{o.have_seed, "--seed"},
                                      std::pair{o.have_elevation, "--elevation"},
                                      std::pair{o.have_terrain, "--terrain"},
                                      std::pair{o.have_density, "--density"}}) {
      if (given) throw vb::InputError("", 0, flag, "cannot be combined with --env (see --help)");
    }
  } else {
    if (!o.have_seed) throw vb::InputError("", 0, "--seed", "required (see --help)");
    if (!o.have_name) throw vb::InputError("", 0, "--name", "required (see --help)");
    if (!o.have_elevation) throw vb::InputError("", 0, "--elevation", "required (see --help)");
    if (!o.have_terrain) throw vb::InputError("", 0, "--terrain", "required (see --help)");
    if (!o.have_density) throw vb::InputError("", 0, "--density", "required (see --help)");
  }
  if (o.out_dir.empty()) throw vb::InputError("", 0, "--out", "required (see --help)");
  if (o.image_dir.empty()) o.image_dir = (fs::path(o.out_dir) / ".." / "data" / "worlds").string();
  return o;
}

int Run(const Options& o) {
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (ec) throw vb::InputError(o.out_dir, 0, "--out", "cannot create directory: " + ec.message());
  fs::create_directories(o.image_dir, ec);
  if (ec) {
    throw vb::InputError(o.image_dir, 0, "--image-dir", "cannot create directory: " + ec.message());
  }

  vb::terrain::TaskSpec task = vb::terrain::GenerateTask(o.gen);
  if (o.scale != 1.0) task = vb::terrain::ScaleTask(task, o.scale);
  const fs::path task_path = fs::path(o.out_dir) / (o.gen.name + ".yaml");
  const fs::path image_path = fs::path(o.image_dir) / (o.gen.name + ".png");
  // stored relative to the task file (and with '/' separators) so the tree can be moved as a whole
  task.height_image = fs::weakly_canonical(image_path)
                          .lexically_relative(fs::weakly_canonical(o.out_dir))
                          .generic_string();
  vb::io::WriteHeightImage(task.heights, task.min_height_m, task.max_height_m, image_path.string());
  vb::io::SaveTask(task, task_path.string());
  if (!o.picture.empty()) vb::io::WriteWorldPicture(task, o.picture);

  const vb::terrain::ElevationStats s = vb::terrain::ComputeElevationStats(
      task.heights, task.size_x_m / (task.heights.cols - 1));
  size_t path_points = 0;
  for (const auto& pair : task.pairs) path_points += pair.path_m.size();
  std::printf("%s: seed %llu, %s elevation, %s terrain, %s obstacles (%zu rocks, %zu trees)\n",
              task.name.c_str(), static_cast<unsigned long long>(task.generator_seed),
              std::string(vb::terrain::ElevationLevelName(task.labels.elevation)).c_str(),
              std::string(vb::terrain::TerrainTypeName(task.labels.terrain)).c_str(),
              std::string(vb::terrain::ObstacleDensityName(task.labels.density)).c_str(),
              task.rocks.size(), task.trees.size());
  std::printf("  elevation: range %.2f m, std %.3f m, mean slope %.1f deg, p95 slope %.1f deg, "
              "max slope %.1f deg, >20 deg %.3f, >30 deg %.3f, roughness %.3f m\n",
              s.range_m, s.std_m, s.mean_slope_deg, s.p95_slope_deg, s.max_slope_deg,
              s.fraction_above_20deg, s.fraction_above_30deg, s.roughness_m);
  std::printf("  pairs: %zu, all connected, %zu path points\n", task.pairs.size(), path_points);
  if (!o.picture.empty()) std::printf("  picture %s\n", o.picture.c_str());
  std::printf("  wrote %s and %s\n", task_path.lexically_normal().string().c_str(),
              image_path.lexically_normal().string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_gen", [&] {
    const Options o = ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(kUsage);
    if (o.version) return vb::io::PrintVersion("vb_gen");
    return Run(o);
  });
}
