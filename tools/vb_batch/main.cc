// vb_batch: runs a benchmark matrix (environments x pairs x vehicles x systems x seeds) in
// parallel worker processes, one forked process per trial, into one resumable output directory.
// docs/batch.md describes the flags, the directory layout, resume and shards.
#include <fcntl.h>
#include <glob.h>
#include <sched.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "io/batch_io.h"
#include "io/result_io.h"
#include "io/task_io.h"
#include "io/vehicle_io.h"
#include "io/yaml_strict.h"
#include "vb/batch/index.h"
#include "vb/batch/matrix.h"
#include "vb/controllers/controller.h"
#include "vb/engine/error.h"
#include "vb/engine/runner/episode.h"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr const char* kUsage = R"(usage: vb_batch ENV... --out DIR [options]

Runs every trial of a matrix in parallel worker processes and writes the results to DIR.
ENV is a task file, a glob (quote it: 'tasks/env0*.yaml') or a directory (all *.yaml in it).

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

struct Options {
  std::vector<std::string> envs;
  std::string pairs = "all";
  std::string vehicles = "hmmwv";
  std::string systems = "pid";
  std::string seeds = "0";
  std::string scales;
  std::string out_dir;
  int jobs = 0;
  std::string shard = "0/1";
  double time_limit_s = vb::runner::EpisodeRules().time_limit_s;
  int traj_every = 1;
  double trial_timeout_s = 0.0;
  bool rerun_stale = false;
  bool quiet = false;
  bool help = false;
};

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

uint64_t ParseU64(const std::string& flag, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || text[0] == '-' || text[0] == '+') {
    throw vb::InputError("", 0, flag, "'" + text + "' is not a non-negative integer");
  }
  return v;
}
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

std::string Join(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// Names from a LIST|all flag, each checked against `valid`.
std::vector<std::string> NameList(const std::string& flag, const std::string& text,
                                  const std::vector<std::string>& valid) {
  if (text == "all") return valid;
  std::vector<std::string> out = Split(text, ',');
  for (const std::string& n : out) {
    if (std::find(valid.begin(), valid.end(), n) == valid.end()) {
      throw vb::InputError("", 0, flag, "unknown name '" + n + "'; valid: " + Join(valid));
    }
  }
  return out;
}

// Task files named by ENV arguments: files as given, globs expanded, directories' *.yaml.
// Sorted and de-duplicated (by absolute path). A name that matches nothing is bad input.
std::vector<std::string> ResolveEnvs(const std::vector<std::string>& envs) {
  std::vector<std::string> files;
  for (const std::string& e : envs) {
    std::error_code ec;
    if (fs::is_directory(e, ec)) {
      size_t found = 0;
      for (const fs::directory_entry& d : fs::directory_iterator(e)) {
        if (d.is_regular_file() && d.path().extension() == ".yaml") {
          files.push_back(d.path().string());
          ++found;
        }
      }
      if (found == 0) throw vb::InputError(e, 0, "ENV", "directory has no *.yaml task files");
    } else if (e.find_first_of("*?[") != std::string::npos) {
      glob_t g;
      const int rc = ::glob(e.c_str(), 0, nullptr, &g);
      if (rc != 0) {
        ::globfree(&g);
        throw vb::InputError(e, 0, "ENV", "glob matches no files");
      }
      for (size_t i = 0; i < g.gl_pathc; ++i) files.push_back(g.gl_pathv[i]);
      ::globfree(&g);
    } else if (fs::is_regular_file(e, ec)) {
      files.push_back(e);
    } else {
      throw vb::InputError(e, 0, "ENV", "no such task file, directory or glob");
    }
  }
  for (std::string& f : files) f = fs::absolute(f).lexically_normal().string();
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

std::string DataDir() {
  const char* env = std::getenv("VB_DATA_DIR");
  return env != nullptr ? env : VB_SOURCE_DIR "/data";
}

int DefaultJobs() {
  cpu_set_t set;
  if (::sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return static_cast<int>(std::max(1L, ::sysconf(_SC_NPROCESSORS_ONLN)));
}

// Loads every task once (labels, pair count, hash). A task that fails to load is kept with its
// error: its trials are recorded as `error`, the batch goes on.
vb::batch::MatrixSpec BuildSpec(const Options& o, const std::vector<std::string>& files) {
  vb::batch::MatrixSpec spec;
  std::vector<double> scales;
  if (!o.scales.empty()) {
    for (const std::string& s : Split(o.scales, ',')) scales.push_back(ParseDouble("--scale", s));
  }
  for (const std::string& f : files) {
    vb::batch::MatrixTask t;
    t.path = f;
    t.name = fs::path(f).stem().string();
    vb::terrain::TaskSpec task;
    task.source_file = f;
    try {
      task = vb::io::LoadTask(f);
      t.name = task.name;
      t.num_pairs = static_cast<int>(task.pairs.size());
      t.scale = task.scale;
      t.elevation = std::string(vb::terrain::ElevationLevelName(task.labels.elevation));
      t.terrain = std::string(vb::terrain::TerrainTypeName(task.labels.terrain));
      t.density = std::string(vb::terrain::ObstacleDensityName(task.labels.density));
    } catch (const vb::InputError& e) {
      t.load_error = e.what();
      t.elevation = t.terrain = t.density = "unknown";
      task.height_image.clear();
    }
    if (!scales.empty() && t.load_error.empty() &&
        std::none_of(scales.begin(), scales.end(),
                     [&](double s) { return std::abs(s - t.scale) <= 1e-9 * std::max(1.0, s); })) {
      continue;
    }
    t.task_fnv1a64 = vb::io::MakeProvenance(task, vb::runner::TrialSpec()).task_fnv1a64;
    spec.tasks.push_back(std::move(t));
  }
  if (!o.pairs.empty() && o.pairs != "all") {
    for (uint64_t p : ParseIntList("--pairs", o.pairs)) {
      if (p > 1000000) throw vb::InputError("", 0, "--pairs", "pair index too large");
      spec.pairs.push_back(static_cast<int>(p));
    }
  }
  spec.vehicles = NameList("--vehicles", o.vehicles, vb::io::VehicleNames(DataDir()));
  spec.systems = NameList("--systems", o.systems, vb::controllers::ControllerNames());
  for (uint64_t s : ParseIntList("--seeds", o.seeds)) spec.seeds.push_back(s);
  return spec;
}

vb::io::Provenance ProvenanceFor(const vb::batch::MatrixTask& t,
                                 const vb::batch::TrialKey& key) {
  vb::terrain::TaskSpec dummy;
  dummy.source_file = t.path;
  vb::runner::TrialSpec spec;
  spec.vehicle = key.vehicle;
  spec.system = key.system;
  spec.seed = key.seed;
  vb::io::Provenance p = vb::io::MakeProvenance(dummy, spec);
  p.task_fnv1a64 = t.task_fnv1a64;
  return p;
}

// The worker: runs one trial in this (forked) process and writes its record. Never returns.
[[noreturn]] void RunWorker(const Options& o, const vb::batch::MatrixTask& t,
                            const vb::batch::TrialKey& key, const std::string& stem_path) {
  int code = 0;
  try {
    if (!t.load_error.empty()) {
      vb::io::WriteUnrunTrialJson(stem_path + ".json", t.name, key.pair, ProvenanceFor(t, key),
                                  "error", t.load_error);
      std::_Exit(0);
    }
    try {
      const vb::terrain::TaskSpec task = vb::io::LoadTask(t.path);
      const vb::vehicles::VehicleParams params =
          vb::io::LoadVehicle(DataDir() + "/vehicles/" + key.vehicle + ".yaml");
      vb::runner::TrialSpec spec;
      spec.pair_index = key.pair;
      spec.seed = key.seed;
      spec.system = key.system;
      spec.vehicle = key.vehicle;
      vb::runner::EpisodeRules rules;
      rules.time_limit_s = o.time_limit_s;
      rules.trajectory_every_n_steps = o.traj_every;
      const vb::runner::TrialResult r = vb::runner::RunTrial(task, params, spec, rules);
      // Trajectory first: a record's presence implies its trajectory is complete.
      vb::io::WriteTrajectoryCsv(r, stem_path + "_traj.csv");
      vb::io::WriteTrialJson(r, stem_path + ".json", vb::io::MakeProvenance(task, spec));
    } catch (const vb::InputError& e) {
      vb::io::WriteUnrunTrialJson(stem_path + ".json", t.name, key.pair, ProvenanceFor(t, key),
                                  "error", e.what());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_batch worker: %s: %s\n", stem_path.c_str(), e.what());
    code = 1;   // the parent records the trial as crashed
  }
  std::fflush(stderr);
  std::_Exit(code);
}

std::string DescribeWaitStatus(int status) {
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    return "worker killed by signal " + std::to_string(sig) + " (" + strsignal(sig) + ")";
  }
  if (WIFEXITED(status)) {
    return "worker exited with code " + std::to_string(WEXITSTATUS(status)) +
           " without a result (internal error, see the batch's stderr)";
  }
  return "worker ended abnormally";
}

std::string Hms(double s) {
  if (!(s >= 0.0) || s > 1e7) return "--:--:--";
  const long t = std::lround(s);
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  return buf;
}

// Set by SIGINT/SIGTERM (Ctrl-C, scancel, a Slurm time limit): stop starting trials, kill the
// running workers (their trials have no record and run again on resume), write the index, exit.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void OnStopSignal(int sig) { g_stop_signal = sig; }

struct Running {
  vb::batch::TrialKey key;
  std::string stem;
  Clock::time_point start;
};

int Run(const Options& o) {
  const vb::batch::Shard shard = vb::batch::ParseShard(o.shard);
  const std::vector<std::string> files = ResolveEnvs(o.envs);
  const vb::batch::MatrixSpec spec = BuildSpec(o, files);
  const std::vector<vb::batch::TrialKey> all = vb::batch::ExpandMatrix(spec);
  const std::vector<vb::batch::TrialKey> mine = vb::batch::SelectShard(all, shard);
  const int jobs = o.jobs > 0 ? o.jobs : DefaultJobs();

  const fs::path out = o.out_dir;
  const fs::path trials_dir = out / "trials";
  std::error_code ec;
  fs::create_directories(trials_dir, ec);
  if (ec) throw vb::InputError(o.out_dir, 0, "--out", "cannot create directory: " + ec.message());

  // One batch per directory at a time (the lock is released when this process ends, even by
  // kill -9).
  const std::string lock_path = (out / ".lock").string();
  const int lock_fd = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd < 0 || ::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
    throw vb::InputError(o.out_dir, 0, "--out", "another vb_batch is running on this directory");
  }
  // Temporary files of writers killed mid-write.
  for (const fs::directory_entry& d : fs::directory_iterator(trials_dir)) {
    if (d.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(d.path(), ec);
  }

  // Settings that change results must match earlier runs into the same directory.
  const std::string settings = "time_limit_s=" + vb::io::FormatDouble(o.time_limit_s) +
                               " traj_every=" + std::to_string(o.traj_every);
  const fs::path settings_path = out / "settings.txt";
  if (fs::exists(settings_path)) {
    std::FILE* f = std::fopen(settings_path.c_str(), "rb");
    char buf[256] = {0};
    const size_t n = f ? std::fread(buf, 1, sizeof(buf) - 1, f) : 0;
    if (f) std::fclose(f);
    std::string old(buf, n);
    while (!old.empty() && old.back() == '\n') old.pop_back();
    if (old != settings) {
      throw vb::InputError(settings_path.string(), 1, "settings",
                           "results in this directory were made with '" + old + "', this run "
                           "uses '" + settings + "'; use another --out");
    }
  } else {
    vb::io::WriteFileAtomic(settings_path.string(), settings + "\n");
  }

  const vb::io::Provenance build = ProvenanceFor(spec.tasks.front(), all.front());
  // Resume: which trials already have a valid record from this build and task version.
  std::vector<vb::batch::TrialKey> todo;
  std::vector<std::string> stale;
  size_t done_before = 0;
  for (const vb::batch::TrialKey& k : mine) {
    const std::string stem = vb::batch::TrialStem(spec, k);
    const fs::path json = trials_dir / (stem + ".json");
    if (!fs::exists(json)) {
      todo.push_back(k);
      continue;
    }
    vb::batch::TrialRow r;
    try {
      r = vb::io::ReadTrialJson(json.string());
    } catch (const vb::InputError& e) {
      std::fprintf(stderr, "vb_batch: warning: unreadable record, re-running: %s\n", e.what());
      todo.push_back(k);
      continue;
    }
    if (r.status == "crashed") {
      todo.push_back(k);
      continue;
    }
    std::string why;
    const std::string& task_hash = spec.tasks[k.task_index].task_fnv1a64;
    if (r.task_fnv1a64 != task_hash) why += " task changed (" + r.task_fnv1a64 + " -> " + task_hash + ")";
    if (r.git_commit != build.git_commit) why += " git commit " + r.git_commit + " -> " + build.git_commit;
    if (r.vb_version != build.vb_version) why += " vb version " + r.vb_version + " -> " + build.vb_version;
    if (why.empty()) {
      ++done_before;
    } else {
      stale.push_back(stem + ":" + why);
      todo.push_back(k);
    }
  }
  if (!stale.empty() && !o.rerun_stale) {
    std::string msg = std::to_string(stale.size()) +
                      " finished trial(s) come from another task version or build:\n";
    for (size_t i = 0; i < stale.size() && i < 10; ++i) msg += "  " + stale[i] + "\n";
    if (stale.size() > 10) msg += "  ...\n";
    msg += "use --rerun-stale to replace them, or another --out";
    throw vb::InputError(o.out_dir, 0, "--out", msg);
  }

  const bool tty = !o.quiet && ::isatty(STDERR_FILENO);
  std::printf("vb_batch: %zu trials in matrix, shard %d/%d: %zu trials, %zu already done, "
              "%zu to run on %d jobs -> %s\n",
              all.size(), shard.index, shard.count, mine.size(), done_before, todo.size(), jobs,
              o.out_dir.c_str());
  std::fflush(stdout);

  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);

  std::map<pid_t, Running> running;
  size_t next = 0, finished = 0, successes = 0, crashed = 0;
  const Clock::time_point t0 = Clock::now();
  Clock::time_point last_draw = t0 - std::chrono::seconds(10);
  auto draw = [&](bool force) {
    if (!tty) return;
    const Clock::time_point now = Clock::now();
    if (!force && now - last_draw < std::chrono::milliseconds(500)) return;
    last_draw = now;
    const double elapsed = std::chrono::duration<double>(now - t0).count();
    const double eta = finished > 0 ? elapsed / finished * (todo.size() - finished) : -1.0;
    const size_t total = todo.size();
    const int width = 30;
    const int filled = total ? static_cast<int>(width * finished / total) : width;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu  success %zu (%.0f%%)  elapsed %s  ETA %s ",
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                 finished, total, successes,
                 finished ? 100.0 * successes / finished : 0.0, Hms(elapsed).c_str(),
                 Hms(eta).c_str());
    std::fflush(stderr);
  };

  while (next < todo.size() || !running.empty()) {
    if (g_stop_signal != 0) {
      for (const auto& [p, r] : running) ::kill(p, SIGKILL);
      for (const auto& [p, r] : running) ::waitpid(p, nullptr, 0);
      running.clear();
      break;
    }
    while (g_stop_signal == 0 && next < todo.size() &&
           static_cast<int>(running.size()) < jobs) {
      const vb::batch::TrialKey& k = todo[next++];
      const std::string stem = vb::batch::TrialStem(spec, k);
      const std::string stem_path = (trials_dir / stem).string();
      std::fflush(stdout);
      std::fflush(stderr);
      const pid_t pid = ::fork();
      if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
      if (pid == 0) {
        ::signal(SIGINT, SIG_DFL);
        ::signal(SIGTERM, SIG_DFL);
        ::close(lock_fd);
        RunWorker(o, spec.tasks[k.task_index], k, stem_path);
      }
      running[pid] = Running{k, stem, Clock::now()};
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid == 0) {
      if (o.trial_timeout_s > 0.0) {
        for (auto& [p, r] : running) {
          if (std::chrono::duration<double>(Clock::now() - r.start).count() > o.trial_timeout_s) {
            ::kill(p, SIGKILL);
          }
        }
      }
      draw(false);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
      continue;
    }
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waitpid failed: ") + std::strerror(errno));
    }
    auto it = running.find(pid);
    if (it == running.end()) continue;
    const Running r = it->second;
    running.erase(it);
    const double wall_s = std::chrono::duration<double>(Clock::now() - r.start).count();
    const std::string json = (trials_dir / (r.stem + ".json")).string();
    std::string result;
    bool have_record = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(json);
    if (have_record) {
      try {
        result = vb::io::ReadTrialJson(json).status;
      } catch (const vb::InputError&) {
        have_record = false;
      }
    }
    if (!have_record) {
      std::string why = DescribeWaitStatus(status);
      if (o.trial_timeout_s > 0.0 && wall_s > o.trial_timeout_s && WIFSIGNALED(status) &&
          WTERMSIG(status) == SIGKILL) {
        why = "wall-clock limit of " + vb::io::FormatDouble(o.trial_timeout_s) + " s exceeded";
      }
      vb::io::WriteUnrunTrialJson(json, spec.tasks[r.key.task_index].name, r.key.pair,
                                  ProvenanceFor(spec.tasks[r.key.task_index], r.key), "crashed",
                                  why);
      result = "crashed";
      ++crashed;
    }
    ++finished;
    if (result == "success") ++successes;
    if (!o.quiet && !tty) {
      std::printf("[%zu/%zu] %s %s (%.1f s wall)\n", finished, todo.size(), r.stem.c_str(),
                  result.c_str(), wall_s);
      std::fflush(stdout);
    }
    draw(finished == todo.size());
  }
  if (tty) std::fputc('\n', stderr);

  // The index, rebuilt from the records of this shard's trials (in matrix order).
  std::vector<vb::batch::TrialRow> rows;
  std::map<std::string, int> counts;
  for (const vb::batch::TrialKey& k : mine) {
    const std::string stem = vb::batch::TrialStem(spec, k);
    const fs::path json = trials_dir / (stem + ".json");
    if (!fs::exists(json)) continue;
    vb::batch::TrialRow r = vb::io::ReadTrialJson(json.string());
    const vb::batch::MatrixTask& t = spec.tasks[k.task_index];
    r.matrix_index = k.matrix_index;
    r.scale = t.scale;
    r.elevation = t.elevation;
    r.terrain = t.terrain;
    r.density = t.density;
    ++counts[r.status];
    rows.push_back(std::move(r));
  }
  vb::io::WriteFileAtomic((out / "index.csv").string(), vb::batch::IndexCsv(rows));
  vb::io::BatchInfo info;
  info.matrix_fingerprint = vb::batch::MatrixFingerprint(spec, all);
  info.matrix_trials = all.size();
  info.shard = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  info.shard_trials = mine.size();
  info.settings = settings;
  info.vb_version = build.vb_version;
  info.git_commit = build.git_commit;
  vb::io::WriteBatchJson(info, (out / "batch.json").string());

  std::string summary;
  for (const auto& [status, n] : counts) {
    summary += (summary.empty() ? "" : ", ") + status + " " + std::to_string(n);
  }
  std::printf("vb_batch: %zu/%zu trials recorded (%s); ran %zu in %.1f s; index %s\n",
              rows.size(), mine.size(), summary.c_str(), finished,
              std::chrono::duration<double>(Clock::now() - t0).count(),
              (out / "index.csv").c_str());
  if (g_stop_signal != 0) {
    std::printf("vb_batch: interrupted by signal %d; run the same command again to resume\n",
                static_cast<int>(g_stop_signal));
    return 128 + g_stop_signal;
  }
  if (crashed > 0) {
    std::printf("vb_batch: %zu trial(s) crashed; run the same command again to retry them\n",
                crashed);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options options = ParseArgs(argc, argv);
    if (options.help) {
      std::fputs(kUsage, stdout);
      return 0;
    }
    return Run(options);
  } catch (const vb::InputError& e) {
    std::fprintf(stderr, "vb_batch: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_batch: internal error: %s\n", e.what());
    return 1;
  }
}
