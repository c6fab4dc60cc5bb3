// A collection mode of vb_collect: what the work items are (a generated world with its episodes,
// or one batch trial) and how one item's episodes are recorded. main.cc owns the directory,
// resume, shards, worker processes and the assembly.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "options.h"
#include "vb/dataset/episode_record.h"
#include "vb/dataset/recorder.h"

namespace vb_collect {

struct WorkItem {
  std::vector<long> episodes;   // dataset episode indices this item records, ascending
};

// Called with each finished episode (index, record): writes its file.
using EpisodeSink = std::function<void(long, const vb::dataset::EpisodeRecord&)>;

class Mode {
 public:
  virtual ~Mode() = default;
  // All work items of the dataset (before sharding), in episode order.
  virtual const std::vector<WorkItem>& items() const = 0;
  // The result-changing settings (settings.txt).
  virtual std::string Settings() const = 0;
  virtual std::string AlgorithmName() const = 0;
  virtual vb::dataset::ActionKind action_kind() const = 0;
  virtual size_t wheels() const = 0;
  // Records the episodes `todo` (a subset of item.episodes) in order, calling sink for each.
  virtual void Run(const WorkItem& item, const std::vector<long>& todo,
                   const EpisodeSink& sink) = 0;
};

std::unique_ptr<Mode> MakeExploreMode(const Options& o);
std::unique_ptr<Mode> MakeFailuresMode(const Options& o);
std::unique_ptr<Mode> MakeDemosMode(const Options& o);
std::unique_ptr<Mode> MakeTeleopMode(const Options& o);

// $VB_DATA_DIR, or the source tree's data/.
std::string DataDir();
// Attributes every episode carries: id, seed, vb version and commit, sampling (docs/datasets.md).
void AddCommonAttributes(const Options& o, long index, uint64_t seed,
                         vb::dataset::EpisodeRecord* r);

}  // namespace vb_collect
