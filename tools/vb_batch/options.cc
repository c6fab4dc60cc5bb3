#include "options.h"

#include <cerrno>
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
  --systems LIST|all   mobility systems (default: pid)
  --seeds LIST         trial seeds, e.g. 0-4 (default: 0)
  --scale LIST         keep only tasks whose world scale is listed, e.g. 1,0.1 (default: all)
execution:
  --out DIR            output directory (required); re-running the same command resumes
  --jobs N             parallel trials (default: CPUs available to this process)
  --shard i/N          run only shard i of N (0-based; every N-th trial of the matrix)
  --time-limit S       simulated time limit per trial (default 60, the benchmark rule)
  --soil NAME          soil parameters data/soils/NAME.yaml for tasks with mud, sand or snow
                       (default: verti_bench, the original's three soils)
  --traj-every N       keep every N-th physics step in the trajectories (default 1)
  --trial-timeout S    wall-clock limit per trial; the worker is killed and the trial recorded
                       as crashed (default 0: none)
  --rerun-stale        re-run trials whose record came from another task version or build
                       (default: report them and stop)
  --quiet              no per-trial lines or progress bar, only the summary
  --help               this text

outputs in DIR: trials/<task>_p<K>_s<seed>_<vehicle>_<system>.json and _traj.csv per trial,
index.csv (one row per finished trial of this shard), batch.json (matrix and settings).
Trial status: success, rollover, stuck, timeout, sim_error (the runner's), error (trial could not
be set up, e.g. unsupported terrain) or crashed (worker died; retried on the next run).

exit codes: 0 every trial has a record; 1 internal error; 2 bad input (flags, stale results,
another vb_batch running on DIR); 130/143 interrupted by SIGINT/SIGTERM (running trials are
stopped, the index is written; run the same command to resume).
)";



std::vector<std::string> Split(const std::string& s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t p = s.find(sep, start);
    out.push_back(s.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) return out;
    start = p + 1;
  }
}

namespace {

uint64_t ParseU64(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || text[0] == '-' || text[0] == '+') {
    throw vb::InputError("", 0, flag, "'" + text + "' is not a non-negative integer");
  }
  return v;
}
}  // namespace

double ParseDouble(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno != 0 || !(v >= 0.0)) {
    throw vb::InputError("", 0, flag, "'" + text + "' is not a valid non-negative number");
  }
  return v;
}

// "0,3,5-9" -> {0, 3, 5, 6, 7, 8, 9}
std::vector<uint64_t> ParseIntList(const std::string& flag, const std::string& text) {
  std::vector<uint64_t> out;
  for (const std::string& item : Split(text, ',')) {
    const size_t dash = item.find('-', 1);
    if (dash == std::string::npos) {
      out.push_back(ParseU64(flag, item));
      continue;
    }
    const uint64_t a = ParseU64(flag, item.substr(0, dash));
    const uint64_t b = ParseU64(flag, item.substr(dash + 1));
    if (b < a || b - a > 100000) throw vb::InputError("", 0, flag, "bad range '" + item + "'");
    for (uint64_t v = a; v <= b; ++v) out.push_back(v);
  }
  return out;
}

Options ParseArgs(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw vb::InputError("", 0, a, "missing value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--pairs") {
      o.pairs = value();
    } else if (a == "--vehicles") {
      o.vehicles = value();
    } else if (a == "--systems") {
      o.systems = value();
    } else if (a == "--seeds") {
      o.seeds = value();
    } else if (a == "--scale") {
      o.scales = value();
    } else if (a == "--out") {
      o.out_dir = value();
    } else if (a == "--jobs") {
      const uint64_t n = ParseU64(a, value());
      if (n < 1 || n > 4096) throw vb::InputError("", 0, a, "must be in [1, 4096]");
      o.jobs = static_cast<int>(n);
    } else if (a == "--shard") {
      o.shard = value();
    } else if (a == "--soil") {
      o.soil = value();
    } else if (a == "--time-limit") {
      o.time_limit_s = ParseDouble(a, value());
      if (!(o.time_limit_s > 0.0)) throw vb::InputError("", 0, a, "must be > 0");
    } else if (a == "--traj-every") {
      const uint64_t n = ParseU64(a, value());
      if (n < 1 || n > 1000000) throw vb::InputError("", 0, a, "must be in [1, 1000000]");
      o.traj_every = static_cast<int>(n);
    } else if (a == "--trial-timeout") {
      o.trial_timeout_s = ParseDouble(a, value());
    } else if (a == "--rerun-stale") {
      o.rerun_stale = true;
    } else if (a == "--quiet") {
      o.quiet = true;
    } else if (!a.empty() && a[0] == '-') {
      throw vb::InputError("", 0, a, "unknown option (see --help)");
    } else {
      o.envs.push_back(a);
    }
  }
  if (o.help) return o;
  if (o.envs.empty()) throw vb::InputError("", 0, "ENV", "no environments given (see --help)");
  if (o.out_dir.empty()) throw vb::InputError("", 0, "--out", "required (see --help)");
  return o;
}

}  // namespace vb_batch
