// vb_batch: runs a benchmark matrix (environments x pairs x vehicles x systems x seeds) in
// parallel worker processes, one forked process per trial, into one resumable output directory.
// docs/batch.md describes the flags, the directory layout, resume and shards. This file: the
// output directory (lock, settings), the resume scan, the scheduler with its progress display,
// and the index.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <utility>
#include <string>
#include <vector>

#include "io/batch_io.h"
#include "io/perception_io.h"
#include "io/cli_args.h"
#include "io/output_dir.h"
#include "io/result_io.h"
#include "io/yaml_strict.h"
#include "options.h"
#include "setup.h"
#include "vb/batch/index.h"
#include "vb/batch/matrix.h"
#include "vb/batch/resume.h"
#include "vb/engine/error.h"
#include "worker.h"

namespace vb_batch {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

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
  int seq = 0;             // its position in the run's todo list (the worker's "computed" signal)
  bool computing = true;   // false once the worker said its trial is computed (it is writing)
};

struct Plan {
  std::vector<vb::batch::TrialKey> todo;
  size_t done_before = 0;
};

// Resume: the trials of `mine` that still need to run (docs/batch.md "Resume"). Stale records
// stop the batch unless --rerun-stale.
Plan PlanResume(const Options& o, const vb::batch::MatrixSpec& spec,
                const std::vector<vb::batch::TrialKey>& mine, const vb::io::Provenance& build) {
  Plan plan;
  std::vector<std::string> stale;
  for (const vb::batch::TrialKey& k : mine) {
    const std::string stem = vb::batch::TrialStem(spec, k);
    const fs::path json = fs::path(o.out_dir) / "trials" / (stem + ".json");
    vb::batch::TrialRow record;
    bool have_record = false;
    if (fs::exists(json)) {
      try {
        record = vb::io::ReadTrialJson(json.string());
        // A record must be this trial's, and a finished trial's trajectory complete: anything
        // else (a record copied under another name, a deleted or cut trajectory) is re-run.
        std::string problem = vb::io::RecordKeyProblem(
            record, spec.tasks[k.task_index].name, k.pair, k.seed, k.vehicle, k.system,
            k.perception);
        if (problem.empty() && record.status != "crashed") {
          const fs::path traj = fs::path(o.out_dir) / "trials" / (stem + "_traj.csv");
          problem = vb::io::TrajectoryProblem(traj.string(), record);
        }
        if (problem.empty()) {
          have_record = true;
        } else {
          std::fprintf(stderr, "vb_batch: warning: %s: %s; re-running\n", json.c_str(),
                       problem.c_str());
        }
      } catch (const vb::InputError& e) {
        std::fprintf(stderr, "vb_batch: warning: unreadable record, re-running: %s\n", e.what());
      }
    }
    const vb::batch::ResumeDecision d =
        vb::batch::DecideResume(have_record ? &record : nullptr,
                                spec.tasks[k.task_index].task_fnv1a64, build.git_commit,
                                build.vb_version);
    if (d.action == vb::batch::ResumeAction::kSkip) {
      ++plan.done_before;
      continue;
    }
    if (d.action == vb::batch::ResumeAction::kStale) stale.push_back(stem + ": " + d.reason);
    plan.todo.push_back(k);
  }
  if (!stale.empty() && !o.rerun_stale) {
    std::string msg = std::to_string(stale.size()) +
                      " finished trial(s) come from another task version or build:\n";
    for (size_t i = 0; i < stale.size() && i < 10; ++i) msg += "  " + stale[i] + "\n";
    if (stale.size() > 10) msg += "  ...\n";
    msg += "use --rerun-stale to replace them, or another --out";
    throw vb::InputError(o.out_dir, 0, "--out", msg);
  }
  return plan;
}

// One line of progress on a terminal: bar, done/total, successes, elapsed time and ETA.
class ProgressBar {
 public:
  ProgressBar(bool enabled, size_t total) : enabled_(enabled), total_(total) {}
  void Draw(size_t finished, size_t successes, bool force) {
    if (!enabled_) return;
    const Clock::time_point now = Clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(500)) return;
    last_draw_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = finished > 0 ? elapsed / finished * (total_ - finished) : -1.0;
    const int width = 30;
    const int filled = total_ ? static_cast<int>(width * finished / total_) : width;
    std::fprintf(stderr, "\r[%s%s] %zu/%zu  success %zu (%.0f%%)  elapsed %s  ETA %s ",
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(),
                 finished, total_, successes, finished ? 100.0 * successes / finished : 0.0,
                 Hms(elapsed).c_str(), Hms(eta).c_str());
    std::fflush(stderr);
  }
  void Finish() {
    if (enabled_) std::fputc('\n', stderr);
  }

 private:
  bool enabled_;
  size_t total_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_draw_ = start_ - std::chrono::seconds(10);
};

struct RunCounts {
  size_t finished = 0, successes = 0, crashed = 0;
  size_t io_failed = 0;   // trials left without a record because a file could not be written
  // The records the workers wrote, as read back when they ended (by matrix index): the index
  // takes them from here instead of reading the files a second time.
  std::map<size_t, vb::batch::TrialRow> records;
};

// Runs `todo` with up to `jobs` forked workers at a time until done or a stop signal; a worker
// that leaves no record becomes a `crashed` record.
RunCounts RunTrials(const Options& o, const vb::batch::MatrixSpec& spec, const ParsedInputs& parsed,
                    const std::vector<vb::batch::TrialKey>& todo, int jobs, int lock_fd) {
  const fs::path trials_dir = fs::path(o.out_dir) / "trials";
  const bool tty = !o.quiet && ::isatty(STDERR_FILENO);
  ProgressBar bar(tty, todo.size());
  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);

  // SIGCHLD stays blocked in the parent so that a worker's end wakes the wait below at once (it
  // is pending even when the worker ended before the wait began); workers get the old mask back.
  // kComputedSignal (a queued real-time signal with the worker's sequence number) says a worker
  // has computed its trial and is writing its files (formatting, fsync: ~5 ms of mostly I/O
  // wait): its slot then starts the next trial. At most 2 x jobs workers exist at a time.
  // The signal is ignored besides: its default action ends the process, and a worker that ended
  // before its signal was taken leaves it pending (drained below before the mask is restored).
  struct sigaction ignore {}, old_computed {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(kComputedSignal, &ignore, &old_computed);
  sigset_t child_ended, old_mask;
  sigemptyset(&child_ended);
  sigaddset(&child_ended, SIGCHLD);
  sigaddset(&child_ended, kComputedSignal);
  ::sigprocmask(SIG_BLOCK, &child_ended, &old_mask);

  std::map<pid_t, Running> running;
  size_t next = 0;
  RunCounts c;
  const pid_t parent = ::getpid();
  // The static worlds (BuildWorld) of the task of todo[next], one per vehicle and perception,
  // each built once and inherited by its trials' workers; dropped when the trials move on to the
  // next task (the matrix is task-major). Built while the workers run (after the slots are
  // filled), so that building costs no slot time.
  std::map<std::pair<std::string, std::string>, std::unique_ptr<vb::runner::Episode>> worlds;
  size_t worlds_task = spec.tasks.size();
  auto prepare_world = [&]() -> vb::runner::Episode* {
    if (next >= todo.size()) {
      worlds.clear();
      return nullptr;
    }
    const vb::batch::TrialKey& k = todo[next];
    if (k.task_index != worlds_task) {
      worlds.clear();
      worlds_task = k.task_index;
    }
    auto [it, inserted] = worlds.try_emplace({k.vehicle, k.perception});
    if (inserted) it->second = BuildWorld(o, parsed, k);
    return it->second.get();
  };
  while (next < todo.size() || !running.empty()) {
    // After a failed write (disk full) starting more trials only burns CPU: let the running ones
    // end, then stop; the trials without a record run on resume.
    if (c.io_failed > 0) next = todo.size();
    if (g_stop_signal != 0) {
      for (const auto& [p, r] : running) ::kill(p, SIGKILL);
      for (const auto& [p, r] : running) ::waitpid(p, nullptr, 0);
      break;
    }
    auto computing = [&]() {
      int n = 0;
      for (const auto& [p, r] : running) n += r.computing;
      return n;
    };
    while (next < todo.size() && computing() < jobs &&
           static_cast<int>(running.size()) < 2 * jobs) {
      vb::runner::Episode* const world = prepare_world();
      const int seq = static_cast<int>(next);
      const vb::batch::TrialKey& k = todo[next++];
      const std::string stem = vb::batch::TrialStem(spec, k);
      std::fflush(stdout);
      std::fflush(stderr);
      const pid_t pid = ::fork();
      if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
      if (pid == 0) {
        DieWithParent(parent);
        ::signal(SIGINT, SIG_DFL);
        ::signal(SIGTERM, SIG_DFL);
        ::sigprocmask(SIG_SETMASK, &old_mask, nullptr);
        ::close(lock_fd);
        RunWorker(o, spec.tasks[k.task_index], parsed, world, k,
                  (trials_dir / stem).string(), seq);
      }
      running[pid] = Running{k, stem, Clock::now(), seq};
    }
    if (c.io_failed == 0 && g_stop_signal == 0) prepare_world();   // the next world, meanwhile
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, WNOHANG);
    if (pid == 0) {   // nothing finished: enforce the wall-clock limit, redraw, poll again
      if (o.trial_timeout_s > 0.0) {
        for (const auto& [p, r] : running) {
          if (std::chrono::duration<double>(Clock::now() - r.start).count() > o.trial_timeout_s) {
            ::kill(p, SIGKILL);
          }
        }
      }
      bar.Draw(c.finished, c.successes, false);
      // Until a worker ends (SIGCHLD), a stop signal arrives (EINTR) or 100 ms pass (redraw,
      // wall-clock limits). Polling with a fixed sleep instead left each of the 2 slots idle for
      // ~10 ms per trial on average (~5 s of a 1000-trial batch).
      const timespec poll{0, 100'000'000};
      siginfo_t info{};
      if (::sigtimedwait(&child_ended, &info, &poll) == kComputedSignal) {
        const auto it = running.find(info.si_pid);
        if (it != running.end() && it->second.seq == info.si_value.sival_int) {
          it->second.computing = false;
        }
      }
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
    if (WIFEXITED(status) && WEXITSTATUS(status) == kWorkerIoFailureExit) {
      // The worker could not write its files (it said why on stderr): no record at all.
      std::error_code ec;
      fs::remove(json, ec);
      ++c.io_failed;
      ++c.finished;
      if (!o.quiet && !tty) {
        std::printf("[%zu/%zu] %s not recorded (I/O error)\n", c.finished, todo.size(),
                    r.stem.c_str());
        std::fflush(stdout);
      }
      continue;
    }
    bool have_record = WIFEXITED(status) && WEXITSTATUS(status) == 0 && fs::exists(json);
    if (have_record) {
      try {
        vb::batch::TrialRow row = vb::io::ReadTrialJson(json);
        result = row.status;
        c.records[r.key.matrix_index] = std::move(row);
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
      try {
        vb::io::WriteUnrunTrialJson(json, spec.tasks[r.key.task_index].name, r.key.pair,
                                    ProvenanceFor(spec.tasks[r.key.task_index], r.key,
                                                  o.rules),
                                    "crashed", why);
      } catch (const vb::IoError& e) {
        std::fprintf(stderr, "vb_batch: I/O error: %s\n", e.what());
        ++c.io_failed;
      }
      result = "crashed";
      ++c.crashed;
    }
    ++c.finished;
    if (result == "success") ++c.successes;
    if (!o.quiet && !tty) {
      std::printf("[%zu/%zu] %s %s (%.1f s wall)\n", c.finished, todo.size(), r.stem.c_str(),
                  result.c_str(), wall_s);
      std::fflush(stdout);
    }
    bar.Draw(c.finished, c.successes, c.finished == todo.size());
  }
  bar.Finish();
  // No worker is left: every "computed" signal that will come is pending now.
  sigset_t computed;
  sigemptyset(&computed);
  sigaddset(&computed, kComputedSignal);
  const timespec no_wait{0, 0};
  while (::sigtimedwait(&computed, nullptr, &no_wait) == kComputedSignal) {
  }
  ::sigprocmask(SIG_SETMASK, &old_mask, nullptr);
  ::sigaction(kComputedSignal, &old_computed, nullptr);
  return c;
}

// The index (rebuilt from the records of this shard's trials, in matrix order) and batch.json.
// Returns the rows.
std::vector<vb::batch::TrialRow> WriteIndex(const Options& o, const vb::batch::MatrixSpec& spec,
                                            const std::vector<vb::batch::TrialKey>& all,
                                            const std::vector<vb::batch::TrialKey>& mine,
                                            const vb::batch::Shard& shard,
                                            const std::string& settings,
                                            const vb::io::Provenance& build,
                                            std::map<size_t, vb::batch::TrialRow>* records) {
  const fs::path out = o.out_dir;
  std::vector<vb::batch::TrialRow> rows;
  for (const vb::batch::TrialKey& k : mine) {
    const fs::path json = out / "trials" / (vb::batch::TrialStem(spec, k) + ".json");
    if (!fs::exists(json)) continue;
    const auto known = records->find(k.matrix_index);
    vb::batch::TrialRow r = known != records->end() ? std::move(known->second)
                                                    : vb::io::ReadTrialJson(json.string());
    const vb::batch::MatrixTask& t = spec.tasks[k.task_index];
    r.matrix_index = k.matrix_index;
    r.scale = t.scale;
    r.elevation = t.elevation;
    r.terrain = t.terrain;
    r.density = t.density;
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
  return rows;
}

int Run(const Options& o) {
  const Clock::time_point t0 = Clock::now();
  const vb::batch::Shard shard = vb::batch::ParseShard(o.shard);
  ParsedInputs parsed;
  const vb::batch::MatrixSpec spec = BuildSpec(o, ResolveEnvs(o.envs), &parsed);
  const std::vector<vb::batch::TrialKey> all = vb::batch::ExpandMatrix(spec);
  const std::vector<vb::batch::TrialKey> mine = vb::batch::SelectShard(all, shard);
  const int jobs = o.jobs > 0 ? o.jobs : DefaultJobs();
  // Everything besides the matrix that changes results: rules, and the parameter files by
  // content (an edited vehicle or soil file must not mix with results made before the edit).
  std::string settings = "time_limit_s=" + vb::io::FormatDouble(o.time_limit_s) +
                         " traj_every=" + std::to_string(o.traj_every) + " soil=" + o.soil + ":" +
                         vb::io::FileFnv1a64Hex(DataDir() + "/soils/" + o.soil + ".yaml");
  // Only when not the benchmark's speed: batches made before the option resume unchanged.
  if (o.target_speed_mps != vb::runner::kDefaultTargetSpeed_mps) {
    settings += " target_speed_mps=" + vb::io::FormatDouble(o.target_speed_mps);
  }
  // Likewise only for other rules than vb's: a directory never holds both.
  if (o.rules != vb::runner::RuleSet::kVb) {
    settings += " rules=" + std::string(vb::runner::RuleSetName(o.rules));
  }
  for (const std::string& v : spec.vehicles) {
    settings +=
        " vehicle=" + v + ":" + vb::io::FileFnv1a64Hex(DataDir() + "/vehicles/" + v + ".yaml");
  }
  for (const std::string& p : spec.perceptions) {
    if (p == "none") continue;  // ground truth has no file (and older batches no such entry)
    settings += " perception=" + p + ":" +
                vb::io::FileFnv1a64Hex(vb::io::PerceptionFile(p, DataDir()));
  }
  const int lock_fd = vb::io::PrepareOutputDir(o.out_dir, "trials", settings, "vb_batch");
  const vb::io::Provenance build = ProvenanceFor(spec.tasks.front(), all.front(), o.rules);
  const Plan plan = PlanResume(o, spec, mine, build);

  std::printf("vb_batch: %zu trials in matrix, shard %d/%d: %zu trials, %zu already done, "
              "%zu to run on %d jobs -> %s\n",
              all.size(), shard.index, shard.count, mine.size(), plan.done_before,
              plan.todo.size(), jobs, o.out_dir.c_str());
  std::fflush(stdout);
  RunCounts c = RunTrials(o, spec, parsed, plan.todo, jobs, lock_fd);
  const std::vector<vb::batch::TrialRow> rows =
      WriteIndex(o, spec, all, mine, shard, settings, build, &c.records);

  std::map<std::string, int> counts;
  for (const vb::batch::TrialRow& r : rows) ++counts[r.status];
  std::string summary;
  for (const auto& [status, n] : counts) {
    summary += (summary.empty() ? "" : ", ") + status + " " + std::to_string(n);
  }
  std::printf("vb_batch: %zu/%zu trials recorded (%s); ran %zu in %.1f s; index %s\n",
              rows.size(), mine.size(), summary.c_str(), c.finished,
              std::chrono::duration<double>(Clock::now() - t0).count(),
              (fs::path(o.out_dir) / "index.csv").c_str());
  if (g_stop_signal != 0) {
    std::printf("vb_batch: interrupted by signal %d; run the same command again to resume\n",
                static_cast<int>(g_stop_signal));
    return 128 + g_stop_signal;
  }
  if (c.crashed > 0) {
    std::printf("vb_batch: %zu trial(s) crashed; run the same command again to retry them\n",
                c.crashed);
  }
  if (c.io_failed > 0) {
    std::fprintf(stderr,
                 "vb_batch: error: %zu trial(s) could not be recorded (I/O error, e.g. disk full; "
                 "see above); fix the cause and run the same command again to run them\n",
                 c.io_failed);
    return 1;
  }
  return 0;
}

}  // namespace
}  // namespace vb_batch

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_batch", [&] {
    const vb_batch::Options o = vb_batch::ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(vb_batch::kUsage);
    if (o.version) return vb::io::PrintVersion("vb_batch");
    return vb_batch::Run(o);
  });
}
