#include "trial_metrics.h"

#include <cmath>

#include "vb/terrain/terrain_physics.h"

namespace vb::runner {

namespace {
constexpr double kRadToDeg = 180.0 / kPi;
}  // namespace

TrajectorySample MakeSample(double t, const vehicles::VehicleState& s,
                            const vehicles::DriverInputs& in) {
  TrajectorySample out;
  out.time_s = t;
  out.position_W = s.pose_W.position;
  out.velocity_W = s.velocity_W;
  out.speed_mps = s.velocity_W.norm();
  out.rpy = s.rpy;
  out.throttle = in.throttle;
  out.steering = in.steering;
  out.braking = in.braking;
  out.gear = s.gear;
  for (const vehicles::WheelState& w : s.wheels) {
    out.wheel_surface.push_back(w.in_contact ? static_cast<int>(w.surface) : -1);
    out.wheel_sinkage_m.push_back(w.sinkage_m);
  }
  return out;
}

TrialMetrics::TrialMetrics(long window_steps, double slow_step_m, size_t obstacle_count,
                           long contact_gap_steps, size_t trajectory_capacity)
    : window_(window_steps),
      slow_(slow_step_m),
      contact_gap_steps_(contact_gap_steps),
      last_touch_step_(obstacle_count, -contact_gap_steps - 1) {
  trajectory_.reserve(trajectory_capacity);
}

void TrialMetrics::StartPosition(const Vec3& position_W) {
  const Vec2 xy = position_W.head<2>();
  window_.Push(xy);
  slow_.Start(position_W);
  last_xy_ = xy;
}

void TrialMetrics::AddStep(const vehicles::VehicleState& s, const vehicles::DriverInputs& inputs,
                           double tipped_roll_rad) {
  if (std::abs(s.rpy.roll_rad) > tipped_roll_rad) tipped_ = true;
  const double roll_deg = s.rpy.roll_rad * kRadToDeg;
  const double pitch_deg = s.rpy.pitch_rad * kRadToDeg;
  roll_.Add(roll_deg);
  pitch_.Add(pitch_deg);
  abs_roll_.Add(std::abs(roll_deg));
  abs_pitch_.Add(std::abs(pitch_deg));
  throttle_.Add(inputs.throttle);
  steering_.Add(inputs.steering);
  abs_steering_.Add(std::abs(inputs.steering));
  const Vec2 xy = s.pose_W.position.head<2>();
  path_length_m_ += (xy - last_xy_).norm();
  last_xy_ = xy;
  window_.Push(xy);
  slow_.Push(s.pose_W.position);
}

void TrialMetrics::AddContacts(long k, const std::vector<engine::ObstacleContact>& contacts,
                               engine::MultiBodyId vehicle_body, size_t rock_count) {
  for (const engine::ObstacleContact& c : contacts) {
    if (c.body != vehicle_body) continue;
    const size_t index = c.obstacle_tag >= terrain::kTreeTagOffset
                             ? rock_count + (c.obstacle_tag - terrain::kTreeTagOffset)
                             : static_cast<size_t>(c.obstacle_tag);
    if (index >= last_touch_step_.size()) continue;
    if (k - last_touch_step_[index] > contact_gap_steps_) ++obstacle_contacts_;
    last_touch_step_[index] = k;
  }
}

void TrialMetrics::Fill(TrialResult* r) const {
  r->path_length_m = path_length_m_;
  r->obstacle_contacts = obstacle_contacts_;
  r->tipped = tipped_;
  r->roll_deg = roll_.Get();
  r->pitch_deg = pitch_.Get();
  r->abs_roll_deg = abs_roll_.Get();
  r->abs_pitch_deg = abs_pitch_.Get();
  r->throttle = throttle_.Get();
  r->steering = steering_.Get();
  r->abs_steering = abs_steering_.Get();
}

}  // namespace vb::runner
