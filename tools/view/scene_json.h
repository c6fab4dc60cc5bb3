// What the browser viewer draws, as JSON (docs/viewer.md "Scene and trial data"): the task's
// world (height grid, semantic patches, obstacle boxes as the physics places them, start/goal
// pairs with their global paths) and the vehicle's schematic geometry (axles, wheels, body box).
// The page cannot read YAML or 16-bit PNG, so the C++ side, which already has the one strict
// loader, digests them; trial files (result JSON, trajectory CSV) are passed through as text
// for the page to parse and check (trial_bundle.h).
#pragma once

#include <string>

#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::view {

// {"name", "file", "size_m", "scale", "goal_radius_m", "heights": {...}, "semantics": {...},
//  "obstacles": [...], "pairs": [...]}. Heights with 0.1 mm resolution, paths with 1 mm.
std::string TaskSceneJson(const terrain::TaskSpec& task, double goal_radius_m);

// {"name", "wheel_radius_m", "wheel_width_m", "max_steer_rad", "axles": [...],
//  "body_min_m", "body_max_m"} in the chassis frame (x forward, y left, z up; origin at the
// reference point). The body box is the bounding box of the chassis envelope; max_steer_rad is
// the road-wheel angle at full steering input (Ackermann: the inner wheel's; rack-pinion: the
// mean of the two sides from the tie-rod geometry).
std::string VehicleSceneJson(const vehicles::VehicleParams& vehicle);

}  // namespace vb::view
