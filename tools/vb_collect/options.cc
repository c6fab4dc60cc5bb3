#include "options.h"

#include <cmath>
#include <string>

#include "io/cli_args.h"
#include "io/data_dir.h"
#include "vb/batch/matrix.h"
#include "vb/engine/error.h"
#include "vb/engine/file_name.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/systems.h"

namespace vb_collect {

const char* const kUsage = R"(usage:
  vb_collect explore  --out DIR [--episodes N] [--world-seed S] [--episodes-per-world K]
                      [--max-episode-s T] [options]
  vb_collect failures --from BATCH_DIR --out DIR [--window-s W] [options]
  vb_collect demos    --out DIR [--episodes N] [--world-seed S] [--episodes-per-world K]
                      [--system NAME] [--time-limit T] [options]
  vb_collect teleop   RECORDING... --out DIR [--keep-failures] [--tasks DIR] [options]

Collects a dataset for learning (docs/datasets.md) in Minari's HDF5 layout: DIR/episodes/ holds
one file per episode (written atomically; a killed run resumes where it stopped), and when every
episode is there DIR/data/main_data.hdf5 + DIR/data/metadata.json are assembled (minari
.load_dataset, h5py, or vb_gym.datasets read them). The same command gives byte-identical files.

Modes:
  explore    random exploration (the paper's protocol): sinusoidal steering at a 2 m/s target
             speed, amplitude and period drawn per episode from its seed; until rollover, stuck,
             leaving the world, or --max-episode-s. Worlds made by the generator (vb_gen) from
             seeds S, S+1, ... outside the benchmark's 0..99, written to DIR/worlds/.
  failures   the last --window-s seconds of every rollover and stuck trial of a vb_batch results
             directory, re-simulated from the trial's task, pair, seed and system (trials are
             deterministic) and labelled with the failure type.
  demos      expert demonstrations: --system (default oracle, the privileged expert that plans
             with vb's own physics) drives from every start of the explore mode's generated
             worlds to the pair's goal under the benchmark's rules; only successes are kept
             (failed episodes leave an empty episode file, left out of the dataset).
  teleop     teleoperated demonstrations: drives recorded by vb_view teleop (RECORDING: a
             drive's <stem>.json beside its <stem>_traj.csv, or a directory searched for them),
             re-simulated from their recorded commands, which must reproduce each drive bit
             for bit (else exit 2 naming the recording); the same schema as demos, and only
             successes are kept unless --keep-failures (kept failures carry failure_type).

Options:
  --out DIR               output directory (required)
  --episodes N            explore, demos: number of episodes (default 10; demos: attempted)
  --world-seed S          explore, demos: generator seed of the first world (default 1000)
  --episodes-per-world K  explore, demos: episodes per world, one per start/goal pair, 1..10
                          (default 10)
  --max-episode-s T       explore: longest episode in simulated seconds (default 300)
  --from BATCH_DIR        failures: a vb_batch results directory (trials/*.json, else index.csv)
  --window-s W            failures: seconds before the trial's end to keep (default 10)
  --time-limit T          failures: the trials' time limit when BATCH_DIR has no settings.txt
                          (a committed report keeps only index.csv; default 60); demos: the
                          trials' time limit (default 60, the benchmark's); teleop: the
                          drives' (default 60, vb_view's)
  --system NAME           demos: the expert (default oracle; any vb_run --system name)
  --keep-failures         teleop: keep drives that did not reach the goal (labelled)
  --tasks DIR             failures, teleop: where task files are found by name when a recorded
                          path does not exist (default: vb's tasks/, as vb_batch finds it)
  --vehicle NAME          data/vehicles/NAME.yaml (explore, demos; default hmmwv)
  --soil NAME             data/soils/NAME.yaml for deformable patches (default verti_bench)
  --sample-period S       seconds between samples, a whole number of 5 ms steps (default 0.1)
  --crops LIST            egocentric crops per sample: elevation, semantics, occupancy, friction
                          (default elevation,semantics; elevation relative to the chassis)
  --crop-size N           cells per crop side (default 64)
  --crop-res M            cell side in metres, times the world scale (default 0.1)
  --dataset-id ID         Minari dataset id (default vb/<mode>-v0)
  --jobs J                worker processes (default 1)
  --shard i/N             collect every N-th work item (world or trial) starting at i
  --rerun-stale           replace episodes made by another build instead of stopping
  --quiet                 no progress lines
  --help                  this text

Exit codes: 0 done, 2 bad input, 1 I/O or other errors, 128+signal when interrupted.
)";

std::string DatasetIdProblem(const std::string& id) {
  // Minari maps "namespace/name-vN" onto directories under MINARI_DATASETS_PATH: each part is
  // a file-name component (no "..", no absolute path), as every other name vb writes.
  const std::vector<std::string> parts = vb::io::SplitList(id, '/');
  if (parts.empty() || parts.size() > kMaxDatasetIdParts) {
    return "'" + id + "': expected 1 to " + std::to_string(kMaxDatasetIdParts) +
           " parts separated by '/' (namespace/name-vN)";
  }
  for (const std::string& part : parts) {
    const std::string problem = vb::FileNameComponentProblem(part, vb::io::kMaxDataNameLength);
    if (!problem.empty()) return "'" + id + "': part '" + part + "': " + problem;
  }
  return "";
}

Options ParseArgs(int argc, char** argv) {
  Options o;
  constexpr double kMaxS = vb::runner::kMaxTimeLimit_s;
  vb::io::ArgReader args(argc, argv);
  bool have_mode = false;
  while (args.Next()) {
    const std::string& a = args.arg();
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--out") o.out_dir = args.Value();
    else if (a == "--dataset-id") o.dataset_id = args.Value();
    else if (a == "--episodes") o.episodes = static_cast<long>(args.U64Value(1, 100000000));
    else if (a == "--world-seed") o.world_seed = args.U64Value();
    else if (a == "--episodes-per-world") {
      o.episodes_per_world = static_cast<int>(args.U64Value(1, 10));
    }
    else if (a == "--max-episode-s") o.max_episode_s = args.PositiveValueAtMost(kMaxS);
    else if (a == "--from") o.from_dir = args.Value();
    else if (a == "--time-limit") o.time_limit_s = args.PositiveValueAtMost(kMaxS);
    else if (a == "--tasks") o.tasks_dir = args.Value();
    else if (a == "--system") o.system = args.Value();
    else if (a == "--window-s") o.window_s = args.PositiveValueAtMost(kMaxS);
    else if (a == "--vehicle") o.vehicle = args.Value();
    else if (a == "--soil") o.soil = args.Value();
    else if (a == "--sample-period") o.sample_period_s = args.PositiveValueAtMost(60.0);
    else if (a == "--crops") o.crops = args.Value();
    else if (a == "--crop-size") o.crop_size = static_cast<int>(args.U64Value(1, 1024));
    else if (a == "--crop-res") o.crop_resolution_m = args.PositiveValueAtMost(100.0);
    else if (a == "--jobs") o.jobs = static_cast<int>(args.U64Value(1, 1024));
    else if (a == "--shard") o.shard = args.Value();
    else if (a == "--rerun-stale") o.rerun_stale = true;
    else if (a == "--keep-failures") o.keep_failures = true;
    else if (a == "--quiet") o.quiet = true;
    else if (args.IsFlag()) args.Unknown();
    else if (!have_mode) {
      o.mode = a;
      have_mode = true;
    } else if (o.mode == "teleop") {
      o.recordings.push_back(a);
    } else {
      throw vb::InputError("", 0, a,
                           "unexpected argument (one mode: explore | failures | demos | teleop)");
    }
  }
  if (o.help) return o;
  if (o.mode != "explore" && o.mode != "failures" && o.mode != "demos" && o.mode != "teleop") {
    const std::string what =
        o.mode.empty() ? std::string("missing") : "'" + o.mode + "' is not valid";
    throw vb::InputError("", 0, "mode",
                         what + "; one of explore | failures | demos | teleop (see --help)");
  }
  if (o.out_dir.empty()) throw vb::InputError("", 0, "--out", "required (see --help)");
  if (o.mode == "failures" && o.from_dir.empty()) {
    throw vb::InputError("", 0, "--from", "required in failures mode (see --help)");
  }
  if (o.mode == "demos") vb::runner::ValidateSystemName(o.system, "--system");
  if (o.mode == "teleop" && o.recordings.empty()) {
    throw vb::InputError("", 0, "RECORDING",
                         "teleop needs recordings of vb_view teleop (files or directories)");
  }
  if (o.tasks_dir.empty()) o.tasks_dir = vb::io::TasksDir();
  // The tools' one name rule (vehicles and soils of the data directory's listings; the failures
  // and teleop modes take the vehicle from their records and check it there).
  if (o.mode == "explore" || o.mode == "demos") {
    vb::io::ListedDataFile(vb::io::DataDir(), "vehicles", o.vehicle, "--vehicle");
  }
  vb::io::ListedDataFile(vb::io::DataDir(), "soils", o.soil, "--soil");
  if (o.dataset_id.empty()) o.dataset_id = "vb/" + o.mode + "-v0";
  const std::string id_problem = DatasetIdProblem(o.dataset_id);
  if (!id_problem.empty()) throw vb::InputError("", 0, "--dataset-id", id_problem);
  vb::batch::ParseShard(o.shard);   // validates
  MakeSampleConfig(o);              // validates crops and the sample period
  return o;
}

vb::dataset::SampleConfig MakeSampleConfig(const Options& o) {
  vb::dataset::SampleConfig c;
  const double step_s = vb::runner::EpisodeRules().step_s;
  const double ratio = o.sample_period_s / step_s;
  const long n = std::lround(ratio);
  if (n < 1 || std::abs(ratio - static_cast<double>(n)) > 1e-9 * ratio) {
    throw vb::InputError("", 0, "--sample-period",
                         "must be a whole number of physics steps of 0.005 s");
  }
  c.sample_every_steps = static_cast<int>(n);
  if (o.crops == "none") return c;
  for (const std::string& name : vb::io::SplitList(o.crops, ',')) {
    vb::dataset::CropSpec s;
    s.name = name;
    if (name == "elevation") s.layer = vb::terrain::MapLayer::kElevation;
    else if (name == "semantics") s.layer = vb::terrain::MapLayer::kSemantics;
    else if (name == "occupancy") s.layer = vb::terrain::MapLayer::kOccupancy;
    else if (name == "friction") s.layer = vb::terrain::MapLayer::kFriction;
    else {
      throw vb::InputError("", 0, "--crops",
                           "unknown layer '" + name +
                               "'; valid: elevation, semantics, occupancy, friction, or none");
    }
    for (const vb::dataset::CropSpec& other : c.crops) {
      if (other.name == name) throw vb::InputError("", 0, "--crops", "'" + name + "' given twice");
    }
    s.size_cells = o.crop_size;
    s.resolution_m = o.crop_resolution_m;
    c.crops.push_back(s);
  }
  return c;
}

}  // namespace vb_collect
