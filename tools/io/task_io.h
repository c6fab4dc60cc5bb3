// Strict reading and writing of task files (docs/task_format.md). yaml-cpp and OpenCV are used
// only in tools/io. Every error is an InputError naming file, line and key.
#pragma once

#include <string>

#include "vb/terrain/task.h"

namespace vb::io {

// Loads and validates a task file and decodes its height image into task.heights.
terrain::TaskSpec LoadTask(const std::string& path);
// The same for task text in memory; `path` names it in messages and locates the height image
// (relative to its directory). The one strict place every task goes through.
terrain::TaskSpec LoadTaskText(const std::string& text, const std::string& path);

// Writes a task file (format version 2, with the obstacle shapes). The height image is written next to it by
// WriteHeightImage; task.height_image must already hold its path relative to the task file.
// The text is loaded back with LoadTaskText before anything is written: a task the loader would
// refuse (a scale out of bounds, a rock outside the world) is an InputError, never a file.
void SaveTask(const terrain::TaskSpec& task, const std::string& path);

// Writes heights as a 16-bit grayscale PNG: pixel = round((h - min)/(max - min) * 65535).
void WriteHeightImage(const terrain::HeightGrid& heights, double min_height_m, double max_height_m,
                      const std::string& path);

}  // namespace vb::io
