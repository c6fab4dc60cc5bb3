#include "io/cli_args.h"
#include "options.h"

#include <cstdlib>

#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace vb_batch {

const char* const kUsage = R"(usage: vb_batch ENV... --out DIR [options]

Runs every trial of a matrix in parallel worker processes and writes the results to DIR.
ENV is a task file, a glob (quote it: 'tasks/env0*.yaml') or a directory (the *.yaml files
directly in it; not recursive).

matrix:
  --pairs all|LIST     start/goal pairs, e.g. 0,3,5-9 (default: all pairs of each task)
  --vehicles LIST|all  vehicles from $VB_DATA_DIR/vehicles (default: hmmwv)
  --systems LIST|all   mobility systems (default: pid): pid, eh, mppi (the paper's classical
                       baselines), rl, mcl, acl (policies trained in vb, docs/learning.md),
                       wmvct, mppi6, tal, tnt (the hybrid baselines, learned models from
                       $VB_DATA_DIR/models), pid_original, eh_original, mppi_original (the
                       original code's variants, docs/baselines.md), straight (PID steering
                       at the goal, not the path: a reference), oracle (the privileged
                       expert; budget variants oracle-h<s>-r<s>-n<k>-e<0|1>; not in "all");
                       --system is the same flag
  --perception LIST    perception presets, e.g. none,mild,moderate,severe (default: none, ground
                       truth); a preset of $VB_DATA_DIR/perception/ (docs/perception.md)
  --seeds LIST         trial seeds, e.g. 0-4 (default: 0)
  --scale LIST         keep only tasks whose world scale is listed, e.g. 1,0.1 (default: all)
execution:
  --out DIR            output directory (required); re-running the same command resumes
  --jobs N             parallel trials (default: CPUs available to this process)
  --shard i/N          run only shard i of N (0-based; every N-th trial of the matrix)
  --time-limit S       simulated time limit per trial, in (0, 3600] (default 60, the benchmark rule)
  --speed V            the systems' target speed in m/s, in (0, 40] (default 4, the original's CLI
                       default at every scale; another speed is not the benchmark: settings.txt
                       and every record say it)
  --rules vb|verti_bench
                       the success and stuck rules (default vb: 10 m planar to the goal, stuck
                       = moved <= 1 m in 10 s; verti_bench: the original's 8 m in 3-D to the
                       marker 2 m above the goal, stuck = 10 s below 2 m/s; docs/task_format.md
                       "Episode rules"). settings.txt, index.csv, the report's system labels and
                       every record say verti_bench
  --soil NAME          soil parameters data/soils/NAME.yaml for tasks with mud, sand or snow
                       (default: verti_bench, the original's three soils)
  --traj-every N       keep every N-th physics step in the trajectories (default 1)
  --trial-timeout S    wall-clock limit per trial; the worker is killed and the trial recorded
                       as crashed (default 0: none)
  --rerun-stale        re-run trials whose record came from another task version or build
                       (default: report them and stop)
  --quiet              no per-trial lines or progress bar, only the summary
  --help               this text
  --version            the version and git commit of this build

outputs in DIR: trials/<task>_p<K>_s<seed>_<vehicle>_<system>[_perc-<preset>].json and _traj.csv
per trial,
index.csv (one row per finished trial of this shard), batch.json (matrix and settings).
Trial status: success, rollover, stuck, timeout, sim_error, out_of_bounds (the runner's), error
(trial could not be set up, e.g. a task file that does not load) or crashed (worker died;
retried on the next run).

exit codes: 0 every trial has a record; 1 internal error, or an I/O error such as a full disk
(the trials left without a record run on resume); 2 bad input (flags, stale results,
another vb_batch running on DIR); 130/143 interrupted by SIGINT/SIGTERM (running trials are
stopped, the index is written; run the same command to resume).
)";



// "0,3,5-9" -> {0, 3, 5, 6, 7, 8, 9}
std::vector<uint64_t> ParseIntList(const std::string& flag, const std::string& text) {
  std::vector<uint64_t> out;
  for (const std::string& item : vb::io::SplitList(text, ',')) {
    const size_t dash = item.find('-', 1);
    if (dash == std::string::npos) {
      out.push_back(vb::io::ParseU64(flag, item));
      continue;
    }
    const uint64_t a = vb::io::ParseU64(flag, item.substr(0, dash));
    const uint64_t b = vb::io::ParseU64(flag, item.substr(dash + 1));
    if (b < a || b - a > 100000) throw vb::InputError("", 0, flag, "bad range '" + item + "'");
    // Counted, not `v <= b`: a range ending at 2^64 - 1 would never end.
    for (uint64_t n = 0; n <= b - a; ++n) out.push_back(a + n);
    if (out.size() > 1000000) throw vb::InputError("", 0, flag, "more than 1000000 values");
  }
  return out;
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
    } else if (a == "--pairs") {
      o.pairs = args.Value();
    } else if (a == "--vehicles") {
      o.vehicles = args.Value();
    } else if (a == "--perception") {
      o.perception = args.Value();
    } else if (a == "--systems" || a == "--system") {
      o.systems = args.Value();
    } else if (a == "--seeds") {
      o.seeds = args.Value();
    } else if (a == "--scale") {
      o.scales = args.Value();
    } else if (a == "--out") {
      o.out_dir = args.Value();
    } else if (a == "--jobs") {
      o.jobs = static_cast<int>(args.U64Value(1, 4096));
    } else if (a == "--shard") {
      o.shard = args.Value();
    } else if (a == "--soil") {
      o.soil = args.Value();
    } else if (a == "--time-limit") {
      o.time_limit_s = args.PositiveValueAtMost(vb::runner::kMaxTimeLimit_s);
    } else if (a == "--speed") {
      o.target_speed_mps = args.PositiveValueAtMost(vb::runner::kMaxTargetSpeed_mps);
    } else if (a == "--rules") {
      o.rules = vb::runner::ParseRuleSet("--rules", args.Value());
    } else if (a == "--traj-every") {
      o.traj_every = static_cast<int>(args.U64Value(1, 1000000));
    } else if (a == "--trial-timeout") {
      o.trial_timeout_s = args.NumberValue();
    } else if (a == "--rerun-stale") {
      o.rerun_stale = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (args.IsFlag()) {
      args.Unknown();
    } else {
      o.envs.push_back(a);
    }
  }
  if (o.help || o.version) return o;
  if (o.envs.empty()) throw vb::InputError("", 0, "ENV", "no environments given (see --help)");
  if (o.out_dir.empty()) throw vb::InputError("", 0, "--out", "required (see --help)");
  return o;
}

}  // namespace vb_batch
