// Per-trial bookkeeping of the episode: signal statistics, driven distance, the stuck window and
// the original's slow-step counter,
// obstacle contact events and the trajectory. Plain copyable data, so an episode snapshot is a
// copy of it. Internal to the runner.
#pragma once

#include <vector>

#include "vb/engine/physics_world.h"
#include "vb/engine/runner/episode.h"
#include "vb/engine/runner/outcome_rules.h"
#include "vb/vehicles/vehicle.h"

namespace vb::runner {

// Welford's running mean and population variance plus the maximum; numerically stable over the
// 12000 steps of a trial and independent of the signal's offset.
class RunningStats {
 public:
  void Add(double x) {
    ++n_;
    const double delta = x - mean_;
    mean_ += delta / static_cast<double>(n_);
    m2_ += delta * (x - mean_);
    max_ = n_ == 1 ? x : std::max(max_, x);
  }
  SignalStats Get() const {
    SignalStats s;
    if (n_ == 0) return s;
    s.mean = mean_;
    s.var = m2_ / static_cast<double>(n_);
    s.max = max_;
    return s;
  }

 private:
  long n_ = 0;
  double mean_ = 0.0;
  double m2_ = 0.0;
  double max_ = 0.0;
};

// Planar positions of the last `window_steps` steps in a ring, so the stuck test ("moved no more
// than d during the last window") is O(1) per step without allocation.
class PositionWindow {
 public:
  PositionWindow() = default;
  explicit PositionWindow(long window_steps)
      : ring_(static_cast<size_t>(window_steps) + 1, Vec2::Zero()) {}
  void Push(const Vec2& p) {
    ring_[head_] = p;
    head_ = (head_ + 1) % ring_.size();
    if (count_ < ring_.size()) ++count_;
  }
  bool Full() const { return count_ == ring_.size(); }
  // Planar displacement between the newest sample and the one `window_steps` steps before it.
  double Displacement() const {
    const Vec2& newest = ring_[(head_ + ring_.size() - 1) % ring_.size()];
    const Vec2& oldest = ring_[head_ % ring_.size()];
    return (newest - oldest).norm();
  }

 private:
  std::vector<Vec2> ring_;
  size_t head_ = 0;
  size_t count_ = 0;
};

// One trajectory row from the vehicle state and the inputs applied during the step that led to it.
TrajectorySample MakeSample(double t, const vehicles::VehicleState& s,
                            const vehicles::DriverInputs& in);

// Everything the episode accumulates while it runs (the result in the making).
class TrialMetrics {
 public:
  TrialMetrics() = default;
  // Starts a trial: the stuck window, the slow-step threshold (verti_bench rules), contact slots
  // for every rock and tree, trajectory capacity.
  TrialMetrics(long window_steps, double slow_step_m, size_t obstacle_count,
               long contact_gap_steps, size_t trajectory_capacity);

  // After every physics step k (>= 1): statistics, path length, stuck window.
  void AddStep(const vehicles::VehicleState& s, const vehicles::DriverInputs& inputs,
               double tipped_roll_rad);
  // Obstacle contact events of step k: a touch starts a new event only after contact_gap_steps
  // out of contact, so a wheel bouncing on a rock face counts once.
  void AddContacts(long k, const std::vector<engine::ObstacleContact>& contacts,
                   engine::MultiBodyId vehicle_body, size_t rock_count);

  const PositionWindow& window() const { return window_; }
  const SlowStepCounter& slow_steps() const { return slow_; }
  std::vector<TrajectorySample>& trajectory() { return trajectory_; }
  const std::vector<TrajectorySample>& trajectory() const { return trajectory_; }
  // Writes the statistics, path length and contact count into *r.
  void Fill(TrialResult* r) const;
  void StartPosition(const Vec3& position_W);

 private:
  RunningStats roll_, pitch_, abs_roll_, abs_pitch_, throttle_, steering_, abs_steering_;
  PositionWindow window_;
  SlowStepCounter slow_;
  Vec2 last_xy_ = Vec2::Zero();
  double path_length_m_ = 0.0;
  int obstacle_contacts_ = 0;
  bool tipped_ = false;
  long contact_gap_steps_ = 0;
  std::vector<long> last_touch_step_;  // per obstacle (rocks first, then trees)
  std::vector<TrajectorySample> trajectory_;
};

}  // namespace vb::runner
