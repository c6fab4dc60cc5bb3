// vb_collect: datasets for learning (docs/datasets.md). This file: the output directory (lock,
// settings), resume, shards, worker processes, and the assembly into Minari's layout; the modes
// (explore.cc, failures.cc, demos.cc, teleop.cc) record episodes with the dataset library
// (vb/dataset).
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/build_info.h"
#include "io/cli_args.h"
#include "io/data_dir.h"
#include "io/hdf5_dataset.h"
#include "io/output_dir.h"
#include "io/yaml_strict.h"
#include "mode.h"
#include "options.h"
#include "vb/batch/matrix.h"
#include "vb/batch/resume.h"
#include "vb/dataset/spaces.h"
#include "vb/engine/error.h"

namespace vb_collect {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::string DataDir() { return vb::io::DataDir(); }

void AddCommonAttributes(const Options& o, long index, uint64_t seed,
                         vb::dataset::EpisodeRecord* r) {
  r->SetInt("id", index);
  r->SetInt("seed", static_cast<int64_t>(seed));
  r->SetInt("total_steps", r->steps);
  r->SetText("vb_version", VB_VERSION);
  r->SetText("git_commit", vb::io::BuildGitCommit());
  std::string crops;
  for (const vb::dataset::CropSpec& c : MakeSampleConfig(o).crops) {
    crops += (crops.empty() ? "" : ",") + c.name + ":" + std::to_string(c.size_cells) + "x" +
             vb::io::FormatDouble(c.resolution_m);
  }
  r->SetText("crops", crops);
}

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void OnStopSignal(int sig) { g_stop_signal = sig; }

constexpr int kWorkerIoFailureExit = 3;
constexpr int kWorkerInputExit = 2;

std::string EpisodeFile(const Options& o, long e) {
  char name[32];
  std::snprintf(name, sizeof(name), "ep%07ld.h5", e);
  return (fs::path(o.out_dir) / "episodes" / name).string();
}

// What resume and assembly find in an episode file (NEW-6 of the probe at 8ff4def: resume took
// any readable file of the same build, so shards made with other flags, or a file with damaged
// data, went into the dataset).
enum class EpisodeFileState {
  kGood,
  kUnreadable,      // missing, cut, or a dataset that does not read back (damaged data)
  kOtherBuild,      // made by another build of vb (--rerun-stale replaces it)
  kOtherSettings,   // made with other settings, or with arrays of other shapes
};

// "crop_size=16 (this run: crop_size=64)": the key=value words of two settings strings that
// differ (all of `theirs` when it has none, an episode file of an older build).
std::string SettingsDifference(const std::string& theirs, const std::string& ours) {
  if (theirs.empty()) return "none recorded (this run: " + ours + ")";
  const std::vector<std::string> a = vb::io::SplitList(theirs, ' ');
  const std::vector<std::string> b = vb::io::SplitList(ours, ' ');
  std::string only_a, only_b;
  for (const std::string& w : a) {
    if (std::find(b.begin(), b.end(), w) == b.end()) only_a += (only_a.empty() ? "" : " ") + w;
  }
  for (const std::string& w : b) {
    if (std::find(a.begin(), a.end(), w) == a.end()) only_b += (only_b.empty() ? "" : " ") + w;
  }
  return only_a + " (this run: " + only_b + ")";
}

// Checks the episode file of episode e against this run: complete and every dataset readable
// (all of its data is read once), its id, its build, the run's settings (the vb_settings
// attribute: crops, sample period, vehicle and soil files, ...) and the shapes of its crops.
EpisodeFileState CheckEpisodeFile(const Options& o, const std::string& settings, long e,
                                  const std::string& path, std::string* why) {
  vb::dataset::EpisodeRecord r;
  try {
    r = vb::io::ReadEpisodeFile(path);
  } catch (const vb::InputError& err) {
    *why = err.what();
    return EpisodeFileState::kUnreadable;
  }
  const auto attr = [&](const char* name) {
    const vb::dataset::Attribute* a = r.FindAttribute(name);
    return a == nullptr ? std::string() : a->text;
  };
  if (attr("id") != std::to_string(e)) {
    *why = path + ": holds episode " + attr("id") + ", not " + std::to_string(e);
    return EpisodeFileState::kUnreadable;
  }
  vb::batch::TrialRow row;
  row.status = attr("status");
  row.git_commit = attr("git_commit");
  row.vb_version = attr("vb_version");
  const vb::batch::ResumeDecision d =
      vb::batch::DecideResume(&row, "", vb::io::BuildGitCommit(), VB_VERSION);
  if (d.action == vb::batch::ResumeAction::kStale) {
    *why = path + ": " + d.reason;
    return EpisodeFileState::kOtherBuild;
  }
  if (attr("vb_settings") != settings) {
    *why = path + ": made with other settings: " + SettingsDifference(attr("vb_settings"), settings);
    return EpisodeFileState::kOtherSettings;
  }
  // An empty episode (a failed demonstration, filtered out) has no arrays to compare.
  for (const vb::dataset::CropSpec& c : MakeSampleConfig(o).crops) {
    if (attr("total_steps") == "0") break;
    const vb::dataset::Column* col = r.Find("observations/" + c.name);
    const std::vector<size_t> want = {static_cast<size_t>(c.size_cells),
                                      static_cast<size_t>(c.size_cells)};
    if (col == nullptr || col->row_shape != want) {
      *why = path + ": observations/" + c.name + " is not " + std::to_string(c.size_cells) +
             " x " + std::to_string(c.size_cells) + " per sample, as this run's crops";
      return EpisodeFileState::kOtherSettings;
    }
  }
  return EpisodeFileState::kGood;
}

// Whether episode e needs recording: no file, an unreadable or damaged one (re-recorded, with a
// warning), or (with --rerun-stale) one made by another build. A file of another build without
// --rerun-stale goes to *stale, one of other settings to *foreign (both refused by the caller).
bool NeedsRun(const Options& o, const std::string& settings, long e,
              std::vector<std::string>* stale, std::vector<std::string>* foreign) {
  const std::string path = EpisodeFile(o, e);
  if (!fs::exists(path)) return true;
  std::string why;
  switch (CheckEpisodeFile(o, settings, e, path, &why)) {
    case EpisodeFileState::kGood:
      return false;
    case EpisodeFileState::kUnreadable:
      std::fprintf(stderr, "vb_collect: warning: %s; re-recording\n", why.c_str());
      return true;
    case EpisodeFileState::kOtherBuild:
      if (o.rerun_stale) return true;
      stale->push_back(why);
      return false;
    case EpisodeFileState::kOtherSettings:
      foreign->push_back(why);
      return false;
  }
  return true;
}

// The refusal of a list of episode files (at most 10 shown).
[[noreturn]] void RefuseEpisodes(const Options& o, const std::vector<std::string>& files,
                                 const std::string& what, const std::string& remedy) {
  std::string msg = std::to_string(files.size()) + " episode file(s) " + what + ":\n";
  for (size_t i = 0; i < files.size() && i < 10; ++i) msg += "  " + files[i] + "\n";
  throw vb::InputError(o.out_dir, 0, "--out", msg + remedy);
}

// In a forked worker: records `items` (with their episodes to do), writes each episode file.
using WorkList = std::vector<std::pair<const WorkItem*, std::vector<long>>>;

[[noreturn]] void RunWorker(const Options& o, Mode& mode, const WorkList& work) {
  int code = 0;
  try {
    const std::string settings = mode.Settings();
    for (const auto& [item, todo] : work) {
      mode.Run(*item, todo, [&](long e, const vb::dataset::EpisodeRecord& r) {
        // Each file carries the settings it was made with: resume and assembly compare them.
        vb::dataset::EpisodeRecord with_settings = r;
        with_settings.SetText("vb_settings", settings);
        vb::io::WriteEpisodeFile(with_settings, EpisodeFile(o, e));
        if (!o.quiet) {
          const vb::dataset::Attribute* status = r.FindAttribute("status");
          const vb::dataset::Attribute* sim = r.FindAttribute("sim_time_s");
          std::printf("episode %ld: %s at %.1f s, %ld steps\n", e, status->text.c_str(), sim->real,
                      r.steps);
          std::fflush(stdout);
        }
      });
    }
  } catch (const vb::InputError& e) {
    std::fprintf(stderr, "vb_collect: error: %s\n", e.what());
    code = kWorkerInputExit;
  } catch (const vb::IoError& e) {
    std::fprintf(stderr, "vb_collect: I/O error: %s\n", e.what());
    code = kWorkerIoFailureExit;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "vb_collect: error: %s\n", e.what());
    code = 1;
  }
  std::fflush(stdout);
  std::fflush(stderr);
  std::_Exit(code);
}

int Run(const Options& o) {
  const Clock::time_point t0 = Clock::now();
  std::unique_ptr<Mode> mode = o.mode == "explore"    ? MakeExploreMode(o)
                              : o.mode == "failures" ? MakeFailuresMode(o)
                              : o.mode == "teleop"   ? MakeTeleopMode(o)
                                                     : MakeDemosMode(o);
  const vb::batch::Shard shard = vb::batch::ParseShard(o.shard);
  const std::string settings = mode->Settings();
  const int lock_fd = vb::io::PrepareOutputDir(o.out_dir, "episodes", settings, "vb_collect");
  const std::vector<WorkItem>& items = mode->items();

  // Resume: what is left of this shard's items.
  WorkList todo;
  std::vector<std::string> stale, foreign;
  long total = 0, left = 0;
  for (size_t i = 0; i < items.size(); ++i) {
    total += static_cast<long>(items[i].episodes.size());
    if (static_cast<int>(i % static_cast<size_t>(shard.count)) != shard.index) continue;
    std::vector<long> episodes;
    for (long e : items[i].episodes) {
      if (NeedsRun(o, settings, e, &stale, &foreign)) episodes.push_back(e);
    }
    left += static_cast<long>(episodes.size());
    if (!episodes.empty()) todo.emplace_back(&items[i], episodes);
  }
  if (!foreign.empty()) {
    RefuseEpisodes(o, foreign, "do not belong to this run",
                   "remove them (or collect them with their own settings into another --out)");
  }
  if (!stale.empty()) {
    RefuseEpisodes(o, stale, "come from another build",
                   "use --rerun-stale to replace them, or another --out");
  }
  const int jobs = std::max(1, std::min<int>(o.jobs, static_cast<int>(todo.size())));
  std::printf("vb_collect %s: %ld episodes in %zu work items, shard %d/%d: %ld to record on %d "
              "job(s) -> %s\n",
              o.mode.c_str(), total, items.size(), shard.index, shard.count, left, jobs,
              o.out_dir.c_str());
  std::fflush(stdout);

  // Workers: job j records the items j, j + jobs, ... of the to-do list.
  struct sigaction sa {};
  sa.sa_handler = OnStopSignal;
  sigemptyset(&sa.sa_mask);
  ::sigaction(SIGINT, &sa, nullptr);
  ::sigaction(SIGTERM, &sa, nullptr);
  std::vector<pid_t> workers;
  const pid_t parent = ::getpid();
  for (int j = 0; j < jobs && !todo.empty(); ++j) {
    WorkList mine;
    for (size_t t = static_cast<size_t>(j); t < todo.size(); t += static_cast<size_t>(jobs)) {
      mine.push_back(todo[t]);
    }
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      if (::getppid() != parent) std::_Exit(1);
      ::signal(SIGINT, SIG_DFL);
      ::signal(SIGTERM, SIG_DFL);
      ::close(lock_fd);
      RunWorker(o, *mode, mine);
    }
    workers.push_back(pid);
  }
  int worst = 0;
  size_t running = workers.size();
  while (running > 0) {
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) {
        if (g_stop_signal != 0) {
          for (pid_t w : workers) ::kill(w, SIGKILL);
        }
        continue;
      }
      break;
    }
    --running;
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : 1;
    if (code != 0 && (worst == 0 || code == kWorkerInputExit)) worst = code;
  }
  const double wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
  if (g_stop_signal != 0) {
    std::printf("vb_collect: interrupted by signal %d; run the same command again to resume\n",
                static_cast<int>(g_stop_signal));
    return 128 + g_stop_signal;
  }
  if (worst != 0) {
    std::fprintf(stderr, "vb_collect: a worker failed (see above); episodes written so far are "
                         "kept, run the same command again to resume\n");
    return worst == kWorkerInputExit ? 2 : 1;
  }

  // Assembly once every episode of the dataset is there (all shards' files in one episodes/).
  // Every file is checked as on resume, those of other shards too (copied in by hand).
  std::vector<std::string> files, bad;
  long missing = 0, left_out = 0;
  double sim_s = 0.0;
  for (const WorkItem& item : items) {
    for (long e : item.episodes) {
      const std::string path = EpisodeFile(o, e);
      if (!fs::exists(path)) {
        ++missing;
        continue;
      }
      std::string why;
      if (CheckEpisodeFile(o, settings, e, path, &why) != EpisodeFileState::kGood) {
        bad.push_back(why);
        continue;
      }
      std::map<std::string, std::string> a = vb::io::ReadEpisodeAttributes(path);
      sim_s += std::atof(a["sim_time_s"].c_str());
      if (a["status"] == "sim_error" || a["total_steps"] == "0") {
        ++left_out;
        continue;
      }
      files.push_back(path);
    }
  }
  std::printf("vb_collect: %ld episodes recorded in %.1f s wall (this run)\n", left, wall_s);
  if (!bad.empty()) {
    RefuseEpisodes(o, bad, "cannot go into the dataset",
                   "re-record them: remove them and run each shard's command again");
  }
  if (missing > 0) {
    std::printf("vb_collect: %ld episode(s) of other shards missing; put all shards' episodes/ "
                "files into one directory and run the command with --shard 0/1 to assemble\n",
                missing);
    return 0;
  }
  vb::io::DatasetInfo info;
  info.dataset_id = o.dataset_id;
  info.observation_space = vb::dataset::ObservationSpaceJson(MakeSampleConfig(o), mode->wheels());
  info.action_space = vb::dataset::ActionSpaceJson(mode->action_kind());
  info.algorithm_name = mode->AlgorithmName();
  info.attributes["vb_mode"] = o.mode;
  info.attributes["vb_settings"] = mode->Settings();
  info.attributes["vb_version"] = VB_VERSION;
  info.attributes["git_commit"] = vb::io::BuildGitCommit();
  info.attributes["vb_action_space"] = vb::dataset::ActionKindName(mode->action_kind());
  const vb::io::AssembleCounts c =
      vb::io::AssembleDataset(files, info, (fs::path(o.out_dir) / "data").string());
  // Simulated hours of all episodes run (kept or not); the kept ones hold steps x sample period.
  std::printf("vb_collect: dataset %s: %ld episodes, %ld steps, %.3f simulated hours%s -> %s\n",
              o.dataset_id.c_str(), c.episodes, c.steps, sim_s / 3600.0,
              left_out > 0 ? (" (" + std::to_string(left_out) +
                              " sim_error/empty/filtered episode(s) left out)")
                                 .c_str()
                           : "",
              (fs::path(o.out_dir) / "data" / "main_data.hdf5").c_str());
  return 0;
}

}  // namespace
}  // namespace vb_collect

int main(int argc, char** argv) {
  return vb::io::ToolMain("vb_collect", [&] {
    const vb_collect::Options o = vb_collect::ParseArgs(argc, argv);
    if (o.help) return vb::io::PrintUsage(vb_collect::kUsage);
    return vb_collect::Run(o);
  });
}
