// Scale variants of an environment for smaller vehicles (the original's scale_factor, 1/6 and
// 1/10): one transform that multiplies every length of a task consistently.
#pragma once

#include <optional>
#include <string_view>

#include "vb/terrain/task.h"

namespace vb::terrain {

// Returns the task with every length multiplied by factor (> 0): world size, heights and height
// range, obstacle positions, start/goal points and paths; task.scale is multiplied too, which
// scales obstacle boxes (terrain_physics.h), the planner inflation (grid_planner.h) and, in the
// runner, the goal radius, stuck distance and the controllers' look-ahead. Grid resolutions, rock
// shape scales and frictions are unchanged, so the occupancy grid in cells is the same.
TaskSpec ScaleTask(const TaskSpec& task, double factor);

// Parses "1/6", "1/10", "0.5" or "1" into a factor > 0; nullopt if malformed or not > 0.
std::optional<double> ParseScaleFactor(std::string_view text);

}  // namespace vb::terrain
