// vb_import: converts an original Verti-Bench world (config YAML + world image, optionally the
// label grid) into a vb task file and height image (docs/importer.md). Thin: argument parsing over
// tools/io/original_io.h and TaskFromOriginal (src/terrain/original_world.cc).
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "io/cli_args.h"
#include "io/original_io.h"
#include "io/task_io.h"
#include "io/world_picture.h"
#include "vb/engine/error.h"
#include "vb/terrain/task.h"
#include "vb/terrain/original_world.h"
#include "vb/terrain/scale.h"

namespace {

namespace fs = std::filesystem;

constexpr const char* kUsage = R"(usage: vb_import --config CONFIG.yaml --world WORLD.bmp
                 [--labels LABELS.npy] --out TASKDIR [--image-dir IMGDIR] [--name NAME]
                 [--scale F] [--picture FILE]

Converts an original Verti-Bench world into a vb task that reproduces its geometry: the 128 m x
128 m terrain from the 129 x 129 world image (h = min_height + p/255 (max_height - min_height)),
the 16 x 16 patches with their classes and frictions, rocks (with their scales) and trees, and the
10 start/goal pairs, each with an A* path on the obstacle grid inflated by 4 m. Imported worlds
are for local use; they are not part of the vb benchmark and are not committed.

  --config FILE      original task config, e.g. config42_low.yaml (required)
  --world FILE       its world image, e.g. 42.bmp: 129 x 129, 8-bit gray (required)
  --labels FILE      its label grid labels42_low.npy (optional): checked against the config
  --out TASKDIR      directory of the task file TASKDIR/NAME.yaml (required; created if missing)
  --image-dir IMGDIR directory of the height image IMGDIR/NAME.png (default: TASKDIR)
  --name NAME        task name and file stem (default: the config's file stem)
  --scale F          scale variant: every length times F (e.g. 1/6, 1/10; default 1)
  --picture FILE     also write a PNG picture of the world
  --help             this text
  --version          the version and git commit of this build

Exit codes: 0 success, 2 bad input (the message names file, line and key), 1 other errors.
)";

struct Options {
  bool help = false;
  bool version = false;
  std::string config, world, labels, out_dir, image_dir, name, picture;
  double scale = 1.0;
};

Options ParseArgs(int argc, char** argv) {
  Options o;
  vb::io::ArgReader args(argc, argv);
  while (args.Next()) {
    const std::string& a = args.arg();
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--version") {
      o.version = true;
    } else if (a == "--config") {
      o.config = args.Value();
    } else if (a == "--world") {
      o.world = args.Value();
    } else if (a == "--labels") {
      o.labels = args.Value();
    } else if (a == "--out") {
      o.out_dir = args.Value();
    } else if (a == "--image-dir") {
      o.image_dir = args.Value();
    } else if (a == "--name") {
      o.name = args.Value();
      const std::string problem = vb::terrain::TaskNameProblem(o.name);
      if (!problem.empty()) throw vb::InputError("", 0, a, problem);
    } else if (a == "--scale") {
      o.scale = args.ScaleValue();
    } else if (a == "--picture") {
      o.picture = args.Value();
    } else {
      args.Unknown();
    }
  }
  if (o.help || o.version) return o;
  if (o.config.empty()) throw vb::InputError("", 0, "--config", "required (see --help)");
  if (o.world.empty()) throw vb::InputError("", 0, "--world", "required (see --help)");
  if (o.out_dir.empty()) throw vb::InputError("", 0, "--out", "required (see --help)");
  if (o.image_dir.empty()) o.image_dir = o.out_dir;
  if (o.name.empty()) {
    o.name = fs::path(o.config).stem().string();
    const std::string problem = vb::terrain::TaskNameProblem(o.name);
    if (!problem.empty()) {
      throw vb::InputError(o.config, 0, "--name", "the config's file stem '" + o.name +
                                                      "' is not a task name (" + problem +
                                                      "); give --name");
    }
  }
  return o;
}

int Run(const Options& o) {
  const vb::io::OriginalWorldFiles files = vb::io::LoadOriginalWorld(o.config, o.world, o.labels);
  vb::terrain::TaskSpec task =
      vb::terrain::TaskFromOriginal(files.config, files.world, o.name, o.config);
  if (o.scale != 1.0) task = vb::terrain::ScaleTask(task, o.scale);

  std::error_code ec;
  for (const std::string& dir : {o.out_dir, o.image_dir}) {
    fs::create_directories(dir, ec);
    if (ec) throw vb::InputError(dir, 0, "", "cannot create directory: " + ec.message());
  }
  const fs::path task_path = fs::path(o.out_dir) / (o.name + ".yaml");
  const fs::path image_path = fs::path(o.image_dir) / (o.name + ".png");
  task.height_image = fs::weakly_canonical(image_path)
                          .lexically_relative(fs::weakly_canonical(o.out_dir))
                          .generic_string();
  // the world image itself, 8-bit: the task reads back exactly the original's heights
  vb::io::WriteGrayImage(files.world, image_path.string());
  vb::io::SaveTask(task, task_path.string());
  if (!o.picture.empty()) vb::io::WriteWorldPicture(task, o.picture);
  std::printf("%s: %s elevation, %s terrain, %s obstacles (%zu rocks, %zu trees), %zu pairs%s\n",
              task.name.c_str(),
              std::string(vb::terrain::ElevationLevelName(task.labels.elevation)).c_str(),
              std::string(vb::terrain::TerrainTypeName(task.labels.terrain)).c_str(),
              std::string(vb::terrain::ObstacleDensityName(task.labels.density)).c_str(),
              task.rocks.size(), task.trees.size(), task.pairs.size(),
              files.labels.empty() ? "" : ", labels checked");
  std::printf("  wrote %s and %s\n", task_path.lexically_normal().string().c_str(),
              image_path.lexically_normal().string().c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_import", [&] {
    const Options o = ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(kUsage);
    if (o.version) return vb::io::PrintVersion("vb_import");
    return Run(o);
  });
}
