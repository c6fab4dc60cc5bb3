// What a mobility system may see, made by the one observation builder
// (include/vb/engine/runner/observation_builder.h) for every consumer: controllers, the gym
// interface, dataset collection and the privileged expert. Ground truth unless a perception model
// is configured (it is applied in the builder and nowhere else; the physics never sees it).
//
// Frames and units: world W is x east, y north, z up (docs/architecture.md); the vehicle frame B
// is ISO 8855 (x forward, y left, z up) at the chassis reference point. SI units, radians.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "vb/engine/types.h"
#include "vb/terrain/gt_maps.h"

namespace vb::controllers {

// One egocentric ground-truth crop to build with every observation (gt_maps.h conventions: row 0
// farthest ahead, column 0 the vehicle's far left, size x size cells of side resolution_m).
struct CropSpec {
  terrain::MapLayer layer = terrain::MapLayer::kElevation;
  int size_cells = 64;
  double resolution_m = 0.1;   // multiplied by the environment scale
};

// What the builder makes besides the robot state (which is always there and cheap).
struct ObservationConfig {
  // Global path: replanned on the inflated obstacle grid from the vehicle's position every
  // replan_period_s of observation time (the original's 10 Hz A*); the local goal is the first
  // path point at least lookahead_m ahead (terrain::LookAheadPoint). Both as the original.
  double lookahead_m = 10.0;          // multiplied by the environment scale
  double replan_period_s = 0.1;
  std::vector<CropSpec> crops;        // built in this order into Observation::crops
  // The crops are rebuilt every crop_period_s of observation time (0: every observation, the
  // default); in between, Observation::crops keeps the last ones. A system that reads its maps
  // only every decision period sets it to that period (the learned systems, 0.1 s) and saves a
  // crop per control step. Rebuilds fall on the same instants as the replans (t = 0, period, ...).
  double crop_period_s = 0.0;
  // Plan the global path as the original's code does (terrain/original_planner.h: its obstacle
  // map with the 129 m addressing, unit-cost A*, one Bezier over the whole path) instead of vb's
  // optimal A*: the `pid_original` system (docs/baselines.md). Plans on the task's obstacles
  // (ground truth), whatever the perception preset.
  bool original_planner = false;
};

// Per wheel (axle-major: axle 0 left, axle 0 right, axle 1 left, ...).
struct WheelObservation {
  bool in_contact = false;
  int surface = -1;                 // terrain::SurfaceClass id under the wheel, -1 airborne
  double normal_force_n = 0.0;
  double sinkage_m = 0.0;           // 0 on rigid ground
  double spin_radps = 0.0;
  // Longitudinal slip (omega r - v) / max(|omega r|, |v|, 0.1 m/s) with v the wheel centre's
  // speed along the wheel heading: + when driving (spinning faster than it travels).
  double slip = 0.0;
};

struct Observation {
  // --- robot state ---
  double time_s = 0.0;
  Vec3 position_W = Vec3::Zero();      // chassis reference point
  Rpy rpy;
  Vec3 velocity_W = Vec3::Zero();      // of the reference point
  Vec3 angular_velocity_B = Vec3::Zero();  // roll, pitch, yaw rates in the vehicle frame
  double forward_speed_mps = 0.0;      // velocity along the chassis x axis
  int gear = 0;
  double engine_speed_radps = 0.0;
  std::vector<WheelObservation> wheels;

  // --- navigation ---
  Vec2 goal_m = Vec2::Zero();
  double goal_distance_m = 0.0;        // planar, reference point to goal
  Vec2 local_goal_m = Vec2::Zero();    // look-ahead point on the global path
  // Bearing of the local goal relative to the heading, wrapped to [-pi, pi): + = to the left.
  double heading_error_rad = 0.0;
  // The current global path (world x, y, start to goal; cell centres of the planning grid).
  // Points into the builder; valid until the next observation.
  const std::vector<Vec2>* global_path_m = nullptr;

  // --- maps ---
  std::vector<terrain::GridMap> crops;  // one per ObservationConfig::crops entry, same order
};

}  // namespace vb::controllers
