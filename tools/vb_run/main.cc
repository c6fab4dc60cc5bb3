// vb_run: runs trials of one task (pairs x one seed x one vehicle x one system) and writes their
// results. Thin on purpose: parse flags -> load -> RunTrial -> write.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/model_store.h"
#include "io/perception_io.h"
#include "io/result_io.h"
#include "io/soil_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "vb/controllers/controller.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/systems.h"

namespace {

constexpr const char* kUsage = R"(usage: vb_run TASK --vehicle NAME [options]

Runs navigation trials on TASK (a task file, e.g. tasks/env042.yaml) and writes their results.

options:
  --vehicle NAME     vehicle description $VB_DATA_DIR/vehicles/NAME.yaml (required);
                     VB_DATA_DIR defaults to share/vb/data next to this program's bin/
  --system NAME      mobility system (default: pid): pid, eh, mppi (the paper's classical
                     baselines), rl, mcl, acl (policies trained in vb, weights from
                     $VB_DATA_DIR/policies; docs/learning.md), wmvct, mppi6, tal, tnt (the
                     hybrid baselines: learned models from $VB_DATA_DIR/models), pid_original,
                     eh_original, mppi_original (the original code's variants,
                     docs/baselines.md), straight
                     (PID steering at the goal, not the path: a reference), oracle (the
                     privileged expert that plans with vb's own physics; budget variants
                     oracle-h<s>-r<s>-n<k>-e<0|1>, docs/baselines.md)
  --soil NAME        soil parameters $VB_DATA_DIR/soils/NAME.yaml for tasks with mud, sand or
                     snow patches (default: verti_bench, the original's three soils)
  --perception NAME  what the system sees: none (ground truth, default), a preset of
                     $VB_DATA_DIR/perception (mild, moderate, severe) or a .yaml file
                     (docs/perception.md)
  --pair K|all       start/goal pair index, or all pairs (default: all)
  --seed S           trial seed, an unsigned 64-bit integer (default: 0)
  --out DIR          output directory (default: results/<task name>/)
  --traj-every N     keep every N-th physics step in the trajectory (default: 1)
  --time-limit S     simulated time limit in seconds, in (0, 3600] (default: 60, the benchmark
                     rule; for tests and quick looks only, results with another limit are not
                     benchmark results)
  --speed V          the systems' target speed in m/s, in (0, 40] (default: 4, the original's
                     CLI default, the same at every scale; the learned systems scale their speed
                     action and observation by it, as the original's RL). Results at another
                     speed are not benchmark results; their records say target_speed_mps
  --rules vb|verti_bench
                     the success and stuck rules (default vb: 10 m planar to the goal, stuck =
                     moved <= 1 m in 10 s; verti_bench: the original's 8 m in 3-D to the marker
                     2 m above the goal, stuck = 10 s below 2 m/s; docs/task_format.md "Episode
                     rules"); records under verti_bench say "rules": "verti_bench"
  --quiet            no per-trial lines, only the final summary
  --help             this text
  --version          the version and git commit of this build

outputs, per trial, in DIR:
  <task>_p<K>_s<seed>_<vehicle>_<system>.json       status, failure type, metrics, provenance
  <task>_p<K>_s<seed>_<vehicle>_<system>_traj.csv   per-step trajectory
(with _perc-<preset> after <system> when --perception is not none)
and DIR/summary.csv with one row per trial of this run (a last "rules" column under
--rules verti_bench). Files are written atomically.

exit codes:
  0  all trials ran (whatever their status: success, rollover, stuck, timeout, sim_error,
     out_of_bounds)
  1  internal error, or an I/O error (a result file cannot be written, e.g. disk full)
  2  bad input (task, vehicle, system, pair, flags); the message names the culprit
)";

struct Options {
  std::string task_path;
  std::string vehicle;
  std::string system = "pid";
  std::string soil = "verti_bench";
  std::string perception = "none";
  std::string pair = "all";
  uint64_t seed = 0;
  std::string out_dir;
  int traj_every = 1;
  double time_limit_s = vb::runner::EpisodeRules().time_limit_s;
  double target_speed_mps = vb::runner::kDefaultTargetSpeed_mps;
  vb::runner::RuleSet rules = vb::runner::RuleSet::kVb;
  bool quiet = false;
  bool help = false;
  bool version = false;
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
    } else if (a == "--vehicle") {
      o.vehicle = args.Value();
    } else if (a == "--system") {
      o.system = args.Value();
    } else if (a == "--soil") {
      o.soil = args.Value();
    } else if (a == "--perception") {
      o.perception = args.Value();
    } else if (a == "--pair") {
      o.pair = args.Value();
    } else if (a == "--seed") {
      o.seed = args.U64Value();
    } else if (a == "--out") {
      o.out_dir = args.Value();
    } else if (a == "--traj-every") {
      o.traj_every = static_cast<int>(args.U64Value(1, 1000000));
    } else if (a == "--time-limit") {
      o.time_limit_s = args.PositiveValueAtMost(vb::runner::kMaxTimeLimit_s);
    } else if (a == "--speed") {
      o.target_speed_mps = args.PositiveValueAtMost(vb::runner::kMaxTargetSpeed_mps);
    } else if (a == "--rules") {
      o.rules = vb::runner::ParseRuleSet("--rules", args.Value());
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (args.IsFlag()) {
      args.Unknown();
    } else if (o.task_path.empty()) {
      o.task_path = a;
    } else {
      throw vb::InputError("", 0, a, "more than one task given (see --help)");
    }
  }
  if (o.help || o.version) return o;
  if (o.task_path.empty()) throw vb::InputError("", 0, "TASK", "no task file given (see --help)");
  if (o.vehicle.empty()) throw vb::InputError("", 0, "--vehicle", "required (see --help)");
  return o;
}

int Run(const Options& o) {
  const std::string data_dir = vb::io::DataDir();
  const vb::io::DataDirModelStore models(data_dir);
  const std::string vehicle_file =
      vb::io::ListedDataFile(data_dir, "vehicles", o.vehicle, "--vehicle");
  vb::runner::ValidateSystemName(o.system, "--system");
  // Checked against the listing even when the task needs no soil: a typo is an error either way,
  // and a name can never reach outside soils/.
  const std::string soil_file = vb::io::ListedDataFile(data_dir, "soils", o.soil, "--soil");
  const vb::terrain::TaskSpec task = vb::io::LoadTask(o.task_path);
  const vb::vehicles::VehicleParams params =
      vb::io::LoadVehicle(vehicle_file);

  // Soil parameters only when the task needs them (a rigid task never reads the soil file).
  const std::optional<vb::soil::SoilConfig> soil = vb::io::LoadSoilIfNeeded(task, soil_file);

  std::vector<int> pairs;
  if (o.pair == "all") {
    for (size_t k = 0; k < task.pairs.size(); ++k) pairs.push_back(static_cast<int>(k));
  } else {
    // Compared as 64-bit: a cast first would wrap 2^32 + 1 to pair 1.
    const uint64_t k = vb::io::ParseU64("--pair", o.pair);
    if (k >= task.pairs.size()) {
      throw vb::InputError(o.task_path, 0, "--pair",
                           "pair " + o.pair + " out of range; task '" + task.name + "' has " +
                               std::to_string(task.pairs.size()) + " pairs (0.." +
                               std::to_string(task.pairs.size() - 1) + ")");
    }
    pairs.push_back(static_cast<int>(k));
  }

  const std::string out_dir = o.out_dir.empty() ? "results/" + task.name : o.out_dir;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw vb::InputError(out_dir, 0, "--out", "cannot create directory: " + ec.message());

  vb::runner::EpisodeRules rules;
  rules.perception = vb::io::ResolvePerception(o.perception, data_dir);
  const std::string perception_file =
      o.perception == "none" ? "" : vb::io::PerceptionFile(o.perception, data_dir);
  rules.time_limit_s = o.time_limit_s;
  rules.target_speed_mps = o.target_speed_mps;
  rules.rule_set = o.rules;
  rules.trajectory_every_n_steps = o.traj_every;
  std::vector<vb::runner::TrialResult> results;
  int counts[vb::runner::kNumTrialStatuses] = {};
  for (int k : pairs) {
    vb::runner::TrialSpec spec;
    spec.pair_index = k;
    spec.seed = o.seed;
    spec.system = o.system;
    spec.vehicle = o.vehicle;
    vb::runner::TrialResult r = vb::runner::RunTrial(task, params, spec, rules, soil ? &*soil : nullptr, &models);
    const std::string stem = out_dir + "/" + vb::io::TrialFileStem(r);
    vb::io::Provenance provenance = vb::io::MakeProvenance(task, spec);
    vb::io::RecordParameterFiles(vehicle_file, o.soil, soil ? soil_file : "", &provenance);
    vb::io::RecordPerception(rules.perception.name, perception_file, &provenance);
    vb::io::WriteTrialFiles(r, stem, provenance);   // trajectory first (as vb_batch)
    ++counts[static_cast<int>(r.status)];
    if (!o.quiet) {
      std::printf("%s pair %d: %-9s t = %6.2f s  goal distance %6.2f m  RTF %.1f%s%s\n",
                  task.name.c_str(), k, std::string(TrialStatusName(r.status)).c_str(),
                  r.sim_time_s, r.final_goal_distance_m, r.real_time_factor,
                  r.status == vb::runner::TrialStatus::kSimError ? "  " : "",
                  r.status == vb::runner::TrialStatus::kSimError ? r.message.c_str() : "");
      std::fflush(stdout);
    }
    results.push_back(std::move(r));
  }
  vb::io::WriteSummaryCsv(results, out_dir + "/summary.csv");

  const double n = std::max<double>(1.0, static_cast<double>(results.size()));
  std::printf("%zu trials: success %d (%.0f%%), rollover %d (%.0f%%), stuck %d (%.0f%%), "
              "timeout %d (%.0f%%), sim_error %d (%.0f%%), out_of_bounds %d (%.0f%%); results in "
              "%s\n",
              results.size(), counts[0], 100.0 * counts[0] / n, counts[1], 100.0 * counts[1] / n,
              counts[2], 100.0 * counts[2] / n, counts[3], 100.0 * counts[3] / n, counts[4],
              100.0 * counts[4] / n, counts[5], 100.0 * counts[5] / n, out_dir.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_run", [&] {
    const Options o = ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(kUsage);
    if (o.version) return vb::io::PrintVersion("vb_run");
    return Run(o);
  });
}
