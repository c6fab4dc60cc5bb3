// Datasets in HDF5 (Debian's libhdf5, C API), in the layout of Minari (Farama's offline-RL
// dataset standard, docs/datasets.md): one file per recorded episode while collecting (written
// atomically, so a killed collection resumes), then the assembled dataset DIR/data/main_data.hdf5
// (groups episode_0 .. episode_{N-1}) with DIR/data/metadata.json. Object time tracking is off
// and nothing else varies between runs, so the same collection gives byte-identical files.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "vb/dataset/episode_record.h"

namespace vb::io {

// Writes `record` as group "/episode" of a new HDF5 file at `path` (built in memory, then
// WriteFileAtomic). Throws IoError naming the path.
void WriteEpisodeFile(const dataset::EpisodeRecord& record, const std::string& path);

// The text, integer and real attributes of an episode file's group, as text (integers in
// decimal, reals with FormatDouble). Throws InputError naming the file if it is not a complete
// episode file.
std::map<std::string, std::string> ReadEpisodeAttributes(const std::string& path);

// Reads an episode file back into columns and attributes (tests, tools). Throws InputError.
dataset::EpisodeRecord ReadEpisodeFile(const std::string& path);

struct DatasetInfo {
  std::string dataset_id;           // Minari id, e.g. "vb/explore-v0"
  std::string observation_space;    // Minari-serialised spaces (vb/dataset/spaces.h)
  std::string action_space;
  std::string algorithm_name;       // e.g. "vb explorer", "pid"
  std::map<std::string, std::string> attributes;   // more root attributes (mode, settings, ...)
};

struct AssembleCounts {
  long episodes = 0;
  long steps = 0;
};

// Copies the episode files, in order, into DATA_DIR/main_data.hdf5 as episode_0, episode_1, ...
// (attribute id renumbered), with the dataset's attributes on the root group, and writes
// DATA_DIR/metadata.json (what minari.load_dataset reads). Both atomic. Throws IoError.
AssembleCounts AssembleDataset(const std::vector<std::string>& episode_files,
                               const DatasetInfo& info, const std::string& data_dir);

}  // namespace vb::io
