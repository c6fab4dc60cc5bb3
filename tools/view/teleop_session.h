// Teleoperation: one episode driven by a person, stepped so that simulated time follows the wall
// clock, with the commands the browser sends (docs/viewer.md "Teleoperation"). The session is
// pure logic over an Episode and a wall time passed in by the caller, so a test can drive it
// with a scripted clock; view_server.cc feeds it the real one and the WebSocket messages.
//
// Client messages (text, one per WebSocket frame; numbers as plain decimals):
//   start                            reset the episode and start the clock (a new drive; refused
//                                    while one is running)
//   command THROTTLE STEERING BRAKING   held from the next control period on; ranges as
//                                    controllers::Command: [0,1], [-1,1] (+ = left), [0,1]
//   stop                             end the drive now (its outcome as it stands)
// The drive also ends by the episode's own rules (goal, rollover, stuck, out of bounds, 60 s).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "vb/controllers/controller.h"
#include "vb/engine/runner/episode.h"
#include "vb/soil/soil_params.h"
#include "vb/terrain/task.h"
#include "vb/vehicles/vehicle_params.h"

namespace vb::view {

struct TeleopOptions {
  int pair = 0;
  uint64_t seed = 0;
  std::string vehicle;                 // vehicle name recorded in the trial (spec.vehicle)
  // Time each command is held before the next one may take over; the episode records a
  // trajectory sample (with the command) every physics step.
  double control_period_s = 0.005;
  // If the simulation falls further behind the wall clock than this (a stalled process), the
  // backlog is dropped instead of being raced through, so the vehicle never jumps.
  double max_lag_s = 0.25;
};

class TeleopSession {
 public:
  // Builds the world once (Episode). Throws InputError as Episode does, or for a pair index out
  // of range.
  TeleopSession(const terrain::TaskSpec& task, const vehicles::VehicleParams& vehicle,
                const soil::SoilConfig* soil, const TeleopOptions& options);
  ~TeleopSession();

  // Applies one client message at wall time `wall_s` (seconds on any monotonic clock). Returns
  // "" or, for a bad message, a description of what is wrong (the session is unchanged).
  std::string HandleMessage(const std::string& text, double wall_s);

  // Steps the running drive until its simulated time has caught up with `wall_s`.
  void AdvanceTo(double wall_s);

  bool driving() const { return driving_; }
  // True once per ended drive, until TakeFinishedDrive.
  bool has_finished_drive() const { return finished_; }
  // The ended drive's result (trajectory included); clears has_finished_drive. A drive ended by
  // "stop" has the message "stopped by the operator at t = T s (outcome as it stood: ...)".
  runner::TrialResult TakeFinishedDrive();
  int drives_started() const { return drives_; }

  // {"type": "state", ...}: time, pose, speeds, command, gear, goal distance, drive status.
  std::string StateJson();
  const controllers::Command& command() const { return command_; }
  const runner::Episode& episode() const { return *episode_; }
  // Wall-clock time dropped because the simulation could not keep up (max_lag_s).
  double slipped_s() const { return slipped_s_; }

 private:
  void EndDrive();

  TeleopOptions options_;
  std::unique_ptr<runner::Episode> episode_;
  controllers::Command command_;
  bool driving_ = false;
  bool finished_ = false;
  bool stopped_ = false;     // the running or last drive was ended by "stop"
  int drives_ = 0;
  double start_wall_s_ = 0.0;
  double slipped_s_ = 0.0;
  std::string end_status_;   // the ended drive's status (Result() would copy the trajectory)
};

}  // namespace vb::view
